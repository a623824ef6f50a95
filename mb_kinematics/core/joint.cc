#include "mb_kinematics/core/joint.h"

#include <stdexcept>
#include <utility>

namespace mbk {
namespace {

const std::pair<const char*, JointType> kNames[] = {
    {"fixed", JointType::kFixed},          {"revolute", JointType::kRevolute},
    {"prismatic", JointType::kPrismatic},  {"ball_123", JointType::kBall123},
    {"ball_euler", JointType::kBallEuler}, {"free_123", JointType::kFree123},
    {"free_euler", JointType::kFreeEuler}, {"planar", JointType::kPlanar},
};

}  // namespace

JointType joint_type_from_string(const std::string& name) {
  for (const auto& entry : kNames)
    if (name == entry.first) return entry.second;
  std::string known;
  for (const auto& entry : kNames) known += std::string(known.empty() ? "" : ", ") + entry.first;
  throw std::invalid_argument("unknown joint type '" + name + "' (known: " + known + ")");
}

std::string to_string(JointType type) {
  for (const auto& entry : kNames)
    if (type == entry.second) return entry.first;
  return "?";
}

const std::vector<std::string>& coordinate_suffixes(JointType type) {
  static const std::vector<std::string> none,
      one = {""}, angles = {"alpha", "beta", "gamma"}, euler = {"e1", "e2", "e3", "e4"},
      free123 = {"x", "y", "z", "alpha", "beta", "gamma"},
      free_euler = {"x", "y", "z", "e1", "e2", "e3", "e4"}, planar = {"x", "y", "gamma"};
  switch (type) {
    case JointType::kFixed:
      return none;
    case JointType::kRevolute:
    case JointType::kPrismatic:
      return one;
    case JointType::kBall123:
      return angles;
    case JointType::kBallEuler:
      return euler;
    case JointType::kFree123:
      return free123;
    case JointType::kFreeEuler:
      return free_euler;
    case JointType::kPlanar:
      return planar;
  }
  return none;
}

int coordinate_count(JointType type) { return static_cast<int>(coordinate_suffixes(type).size()); }

bool uses_euler_parameters(JointType type) {
  return type == JointType::kBallEuler || type == JointType::kFreeEuler;
}

int speed_count(JointType type, SpeedKind speeds) {
  const int n = coordinate_count(type);
  return uses_euler_parameters(type) && speeds == SpeedKind::kAngularVelocity ? n - 1 : n;
}

}  // namespace mbk
