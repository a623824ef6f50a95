// Eigen values into geometry_msgs fields, for the node's outputs and mbk bag alike.
#pragma once

#include <Eigen/Geometry>

#include "mb_kinematics/core/types.h"

namespace mbk_messages {

// x, y, z of a Vector3, Point or the like.
template <typename T>
void set_vector(const mbk::Vec3<double>& v, T& out) {
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
}

template <typename T>
void set_quaternion(const Eigen::Quaterniond& q, T& out) {
  out.x = q.x();
  out.y = q.y();
  out.z = q.z();
  out.w = q.w();
}

template <typename T>
void set_quaternion(const mbk::Mat3<double>& rotation, T& out) {
  set_quaternion(Eigen::Quaterniond(rotation), out);
}

}  // namespace mbk_messages
