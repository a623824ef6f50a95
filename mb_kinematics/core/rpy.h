// URDF roll-pitch-yaw angles to a rotation matrix: R = Rz(yaw) Ry(pitch) Rx(roll).
#pragma once

#include "mb_kinematics/core/types.h"

namespace mbk {

inline Mat3<double> rotation_from_rpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Vec3<double>::UnitZ()) *
          Eigen::AngleAxisd(pitch, Vec3<double>::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3<double>::UnitX()))
      .toRotationMatrix();
}

}  // namespace mbk
