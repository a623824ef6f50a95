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

[[noreturn]] void fail(const std::string& path, const YAML::Node& node, const std::string& what) {
  throw std::invalid_argument(
      printable(path + ":" + std::to_string(node.Mark().line + 1) + ": " + what));
}

std::string name_of(const std::string& path, const YAML::Node& node, const std::string& field) {
  if (!node.IsScalar() || node.as<std::string>().empty())
    fail(path, node, field + ": expected a joint name");
  return node.as<std::string>();
}

// A joint name, a list of names or {end_site: NAME}.
MapPoint point_of(const std::string& path, const YAML::Node& node, const std::string& field) {
  MapPoint p;
  if (node.IsScalar()) {
    p.joints.push_back(name_of(path, node, field));
  } else if (node.IsSequence() && node.size() > 0) {
    for (const YAML::Node& joint : node) p.joints.push_back(name_of(path, joint, field));
  } else if (node.IsMap() && node.size() == 1 && node["end_site"]) {
    p.joints.push_back(name_of(path, node["end_site"], field));
    p.end_site = true;
  } else {
    fail(path, node, field + ": expected a joint name, a list of them or {end_site: NAME}");
  }
  return p;
}

// The ends the table places itself, which a map cannot give: XYPH and OMPH between the trunk
// parts.
bool placed_by_table(const std::string& segment, const std::string& end) {
  return (segment == "upper_trunk" && end == "distal") || segment == "middle_trunk" ||
         (segment == "lower_trunk" && end == "proximal");
}

MappedSegment full_entry(const std::string& path, const std::string& segment,
                         const YAML::Node& node) {
  MappedSegment s;
  s.line = node.Mark().line + 1;
  for (const auto& field : node) {
    const std::string name = field.first.IsScalar() ? field.first.as<std::string>() : "";
    if (name == "joint") {
      s.joint = name_of(path, field.second, segment + ": joint");
      continue;
    }
    if (name != "proximal" && name != "distal")
      fail(path, field.first,
           segment + ": '" + name + "' is not a field (joint, proximal, distal)");
    if (placed_by_table(segment, name))
      fail(path, field.first,
           segment + ": its " + name +
               " end is placed by the table's trunk part lengths (give upper_trunk's proximal, "
               "SUPR, and lower_trunk's distal, MIDH)");
    (name == "proximal" ? s.proximal : s.distal) =
        point_of(path, field.second, segment + ": " + name);
  }
  return s;
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
  std::map<std::string, std::string> given_by;  // segment -> what gave it, for the second use
  for (const auto& entry : root) {
    if (!entry.first.IsScalar() || !(entry.second.IsScalar() || entry.second.IsMap()))
      fail(path, entry.first, "expected joint name: segment, or segment: {joint: ...}");
    const std::string key = entry.first.as<std::string>();
    const bool full = entry.second.IsMap();
    const std::string segment = full ? key : entry.second.as<std::string>();
    if (!is_key(segment))
      throw std::invalid_argument(printable(path + ": " + (full ? "" : "joint " + key + ": ") +
                                            "'" + segment + "' is not a segment (" +
                                            name_list(segment_keys()) + ")"));
    const std::string by =
        full ? "the entry at line " + std::to_string(entry.first.Mark().line + 1) : key;
    const auto [it, fresh] = given_by.emplace(segment, by);
    if (!fresh)
      throw std::invalid_argument(
          printable(path + ": " + segment + " given to two joints, " + it->second + " and " + by));
    if (full) {
      map.segment[segment] = full_entry(path, segment, entry.second);
    } else {
      map.segment[segment].joint = key;
      map.segment[segment].line = entry.first.Mark().line + 1;
    }
  }
  return map;
}

SegmentMap read_segment_map(const std::string& path) {
  return parse_segment_map(read_text_file(path, "segment map"), path);
}

}  // namespace mbk
