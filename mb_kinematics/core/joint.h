// Joints: how body Bk moves relative to its lower body Bj (doc/method.md 2 and 3), and the facts
// about each joint type in one table (joint_traits). Adding a joint type touches these three
// files only: JointType here, its row in joint.cc's table, and its motion in joint_motion.h
// (joint_motion, joint_quaternion); the compiler (-Wswitch-enum) flags every switch over
// JointType, none has a default. The recursion runs a new type through joint_motion
// (JointKernel::kGeneric) until it earns a kernel of its own (body_step.cc, kinematics.h).
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/euler_order.h"
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
  kUniversal,  // Hooke joint: alpha about the joint frame's x, then beta about the new y: A B
  kLast =
      kUniversal,  // keep equal to the last type (all_joint_types() checks its length against it)
};

// How generalized speeds of Euler-parameter joints are chosen (doc/method.md 5): the time
// derivatives of e1..e4, or the relative angular velocity components in Bj ("quasi-coordinates",
// Table 4.3.10). Every other joint always uses coordinate derivatives.
enum class SpeedKind { kCoordinateDerivatives, kAngularVelocity };

// What a coordinate is: angles may grow without bound, translations and Euler parameters may not.
enum class CoordinateKind { kAngle, kTranslation, kEulerParameter };

struct Coordinate {
  const char*
      suffix;  // "" for one-coordinate joints (named after the joint), else "x", "alpha", "e4", ...
  CoordinateKind kind;
};

// How `mbk urdf` writes a joint of the type.
enum class UrdfForm {
  kJoint,      // one URDF joint of type `urdf_type`
  kAxisChain,  // a one-axis URDF joint per coordinate through massless links: translations
               // prismatic along x, y, z of the joint frame, then angles continuous about the
               // new x, y, z (1-2-3)
  kNone,       // no URDF equivalent
};

struct JointTraits {
  const char* name;  // in scenes and on the command line
  // In coordinate order; translations come first, and the speeds follow the same order: a
  // translation's speed is its rate (a linear speed), the others turn the body. With
  // SpeedKind::kAngularVelocity, the four Euler parameters have three speeds wx, wy, wz instead.
  std::vector<Coordinate> coordinates;
  bool uses_axis;         // Joint::axis: revolute and prismatic axis, planar normal
  const char* urdf_type;  // the URDF joint type it is read from and written as ("" if none)
  UrdfForm urdf_form;
};

const JointTraits& joint_traits(JointType type);
const std::vector<JointType>& all_joint_types();  // in JointType order

// Names used in scene files and on the command line: fixed, revolute, prismatic, ball_123,
// ball_euler, free_123, free_euler, planar, universal. Throws std::invalid_argument for an unknown
// name.
JointType joint_type_from_string(const std::string& name);
std::string to_string(JointType type);
// The type read from a URDF joint type (JointTraits::urdf_type; "revolute" is read as
// "continuous", its limits aside). Throws std::invalid_argument for a type without one.
JointType joint_type_from_urdf_type(const std::string& urdf_type);

// Coordinate suffixes of a joint type, in coordinate order: {} for fixed, {""} for the
// one-coordinate joints (the coordinate is named after the joint), else e.g. {"x","y","z",...}.
const std::vector<std::string>& coordinate_suffixes(JointType type);
// Speed suffixes: the coordinate suffixes, except wx, wy, wz for Euler parameters with
// angular velocity speeds.
std::vector<std::string> speed_suffixes(JointType type, SpeedKind speeds);
CoordinateKind coordinate_kind(JointType type, int i);
int coordinate_count(JointType type);
int speed_count(JointType type, SpeedKind speeds);
int translation_count(JointType type);  // leading translation coordinates (= linear speeds)
bool uses_euler_parameters(JointType type);
int first_euler_parameter(JointType type);  // index of e1 among the joint's coordinates; -1 if none
// Ball and free joints with angles (kBall123, kFree123): they take Joint::euler_order.
bool takes_euler_order(JointType type);

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  Vec3<double> axis = Vec3<double>::UnitZ();         // unit; revolute, prismatic, planar normal
  Vec3<double> offset = Vec3<double>::Zero();        // q_k: O_j -> Q_k, components in Bj
  Mat3<double> rotation = Mat3<double>::Identity();  // C_k: SJK = C_k * R_motion(coordinates)
  // kBall123, kFree123: the axes of alpha, beta, gamma (euler_order.h), any of the 12 orders:
  // SJK = C_k R_a1(alpha) R_a2(beta) R_a3(gamma). The others ignore it.
  EulerOrder euler_order = EulerOrder::kXYZ;
};

}  // namespace mbk
