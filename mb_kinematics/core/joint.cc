#include "mb_kinematics/core/joint.h"

#include <stdexcept>

#include "mb_kinematics/core/printable.h"

namespace mbk {

// The table of joint facts (doc/method.md 2; coordinates as in doc/conventions.md "Coordinates and
// conventions").
const JointTraits& joint_traits(JointType type) {
  constexpr CoordinateKind a = CoordinateKind::kAngle, t = CoordinateKind::kTranslation,
                           e = CoordinateKind::kEulerParameter;
  static const JointTraits fixed{"fixed", {}, false, "fixed", UrdfForm::kJoint},
      revolute{"revolute", {{"", a}}, true, "continuous", UrdfForm::kJoint},
      prismatic{"prismatic", {{"", t}}, true, "prismatic", UrdfForm::kJoint},
      ball_123{
          "ball_123", {{"alpha", a}, {"beta", a}, {"gamma", a}}, false, "", UrdfForm::kAxisChain},
      ball_euler{
          "ball_euler", {{"e1", e}, {"e2", e}, {"e3", e}, {"e4", e}}, false, "", UrdfForm::kNone},
      free_123{"free_123",
               {{"x", t}, {"y", t}, {"z", t}, {"alpha", a}, {"beta", a}, {"gamma", a}},
               false,
               "floating",
               UrdfForm::kAxisChain},
      free_euler{"free_euler",
                 {{"x", t}, {"y", t}, {"z", t}, {"e1", e}, {"e2", e}, {"e3", e}, {"e4", e}},
                 false,
                 "",
                 UrdfForm::kNone},
      planar{"planar", {{"x", t}, {"y", t}, {"gamma", a}}, true, "planar", UrdfForm::kJoint},
      universal{"universal", {{"alpha", a}, {"beta", a}}, false, "", UrdfForm::kAxisChain};
  switch (type) {
    case JointType::kFixed:
      return fixed;
    case JointType::kRevolute:
      return revolute;
    case JointType::kPrismatic:
      return prismatic;
    case JointType::kBall123:
      return ball_123;
    case JointType::kBallEuler:
      return ball_euler;
    case JointType::kFree123:
      return free_123;
    case JointType::kFreeEuler:
      return free_euler;
    case JointType::kPlanar:
      return planar;
    case JointType::kUniversal:
      return universal;
  }
  throw std::invalid_argument("joint type " + std::to_string(static_cast<int>(type)) +
                              " is not a JointType");
}

const std::vector<JointType>& all_joint_types() {
  static const std::vector<JointType> types = [] {
    std::vector<JointType> v;
    for (int i = 0; i <= static_cast<int>(JointType::kLast); ++i)
      v.push_back(static_cast<JointType>(i));
    return v;
  }();
  return types;
}

JointType joint_type_from_string(const std::string& name) {
  std::string known;
  for (JointType type : all_joint_types()) {
    if (name == joint_traits(type).name) return type;
    known += std::string(known.empty() ? "" : ", ") + joint_traits(type).name;
  }
  throw std::invalid_argument("unknown joint type '" + printable(name) + "' (known: " + known +
                              ")");
}

std::string to_string(JointType type) { return joint_traits(type).name; }

JointType joint_type_from_urdf_type(const std::string& urdf_type) {
  const std::string name = urdf_type == "revolute" ? "continuous" : urdf_type;
  for (JointType type : all_joint_types())
    if (!name.empty() && name == joint_traits(type).urdf_type) return type;
  throw std::invalid_argument("URDF joint type '" + printable(urdf_type) +
                              "' has no joint type here");
}

const std::vector<std::string>& coordinate_suffixes(JointType type) {
  static const std::vector<std::vector<std::string>> suffixes = [] {
    std::vector<std::vector<std::string>> all;
    for (JointType t : all_joint_types()) {
      all.emplace_back();
      for (const Coordinate& c : joint_traits(t).coordinates) all.back().push_back(c.suffix);
    }
    return all;
  }();
  return suffixes.at(static_cast<size_t>(type));
}

std::vector<std::string> speed_suffixes(JointType type, SpeedKind speeds) {
  std::vector<std::string> out = coordinate_suffixes(type);
  if (speed_count(type, speeds) == coordinate_count(type)) return out;
  out.resize(first_euler_parameter(type));  // angular velocity components replace e1..e4
  for (const char* w : {"wx", "wy", "wz"}) out.push_back(w);
  return out;
}

CoordinateKind coordinate_kind(JointType type, int i) {
  return joint_traits(type).coordinates.at(static_cast<size_t>(i)).kind;
}

int coordinate_count(JointType type) {
  return static_cast<int>(joint_traits(type).coordinates.size());
}

int translation_count(JointType type) {
  int n = 0;
  for (const Coordinate& c : joint_traits(type).coordinates)
    n += c.kind == CoordinateKind::kTranslation;
  return n;
}

int first_euler_parameter(JointType type) {
  const auto& coordinates = joint_traits(type).coordinates;
  for (size_t i = 0; i < coordinates.size(); ++i)
    if (coordinates[i].kind == CoordinateKind::kEulerParameter) return static_cast<int>(i);
  return -1;
}

bool uses_euler_parameters(JointType type) { return first_euler_parameter(type) >= 0; }

bool takes_euler_order(JointType type) {
  return type == JointType::kBall123 || type == JointType::kFree123;
}

int speed_count(JointType type, SpeedKind speeds) {
  const int n = coordinate_count(type);
  return uses_euler_parameters(type) && speeds == SpeedKind::kAngularVelocity ? n - 1 : n;
}

}  // namespace mbk
