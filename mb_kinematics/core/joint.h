// Joints: how body Bk moves relative to its lower body Bj (method.md 2 and 3).
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/types.h"

namespace mbk {

enum class JointType {
  kFixed,      // no coordinates
  kRevolute,   // one angle about `axis` (URDF revolute and continuous)
  kPrismatic,  // one translation along `axis`
  kBall123,    // 1-2-3 angles alpha, beta, gamma (eq. 4.4.9-4.4.12)
  kBallEuler,  // Euler parameters e1, e2, e3 (vector part), e4 (scalar part) (eq. 4.3.1)
  kFree123,    // translations x, y, z then 1-2-3 angles: the chapter's general 6-coordinate joint
  kFreeEuler,  // translations x, y, z then Euler parameters e1..e4
  kPlanar,     // translations x, y in the plane normal to `axis`, rotation gamma about it
};

// How generalized speeds of Euler-parameter joints are chosen (method.md 5): the time
// derivatives of e1..e4, or the relative angular velocity components in Bj ("quasi-coordinates",
// Table 4.3.10). Every other joint always uses coordinate derivatives.
enum class SpeedKind { kCoordinateDerivatives, kAngularVelocity };

// Names used in scene files and on the command line: fixed, revolute, prismatic, ball_123,
// ball_euler, free_123, free_euler, planar. Throws std::invalid_argument for an unknown name.
JointType joint_type_from_string(const std::string& name);
std::string to_string(JointType type);

// Coordinate suffixes of a joint type, in coordinate order: {} for fixed, {""} for the
// one-coordinate joints (the coordinate is named after the joint), else e.g. {"x","y","z",...}.
const std::vector<std::string>& coordinate_suffixes(JointType type);
int coordinate_count(JointType type);
int speed_count(JointType type, SpeedKind speeds);
bool uses_euler_parameters(JointType type);

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  Vec3<double> axis = Vec3<double>::UnitZ();         // unit; revolute, prismatic, planar normal
  Vec3<double> offset = Vec3<double>::Zero();        // q_k: O_j -> Q_k, components in Bj
  Mat3<double> rotation = Mat3<double>::Identity();  // C_k: SJK = C_k * R_motion(coordinates)
};

}  // namespace mbk
