#include "mb_kinematics/io/bvh_segment_map.h"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/name_list.h"
#include "mb_kinematics/io/text_file.h"

namespace mbk {
namespace {

bool is_key(const std::string& segment) {
  for (const std::string& key : segment_keys())
    if (key == segment) return true;
  return false;
}

}  // namespace

const std::vector<std::string>& segment_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k = {"head", "upper_trunk", "middle_trunk", "lower_trunk"};
    for (const char* side : {"left_", "right_"})
      for (const char* part : {"upper_arm", "forearm", "hand", "thigh", "shank", "foot"})
        k.push_back(std::string(side) + part);
    return k;
  }();
  return keys;
}

SegmentMap parse_segment_map(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(path + ": not YAML: " + e.msg);
  }
  if (!root.IsMap()) throw std::invalid_argument(path + ": expected a map of joint name: segment");
  SegmentMap map;
  map.path = path;
  std::map<std::string, std::string> joint_of;  // segment -> joint, for the second use
  for (const auto& entry : root) {
    if (!entry.first.IsScalar() || !entry.second.IsScalar())
      throw std::invalid_argument(path + ":" + std::to_string(entry.first.Mark().line + 1) +
                                  ": expected joint name: segment");
    const std::string joint = entry.first.as<std::string>();
    const std::string segment = entry.second.as<std::string>();
    if (!is_key(segment))
      throw std::invalid_argument(printable(path + ": joint " + joint + ": '" + segment +
                                            "' is not a segment (" + name_list(segment_keys()) +
                                            ")"));
    const auto [it, fresh] = joint_of.emplace(segment, joint);
    if (!fresh)
      throw std::invalid_argument(printable(path + ": " + segment + " given to two joints, " +
                                            it->second + " and " + joint));
    map.segment_of[joint] = segment;
  }
  return map;
}

SegmentMap read_segment_map(const std::string& path) {
  return parse_segment_map(read_text_file(path, "segment map"), path);
}

}  // namespace mbk
