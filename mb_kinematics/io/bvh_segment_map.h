// A user's map from a BVH skeleton's joints to the anthropometric table's segments
// (`--segments FILE`, doc/anthropometry.md#a-map-of-your-own), for skeletons whose names the
// naming rules miss: a YAML map `joint name: segment`. ROS-free.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mbk {

struct SegmentMap {
  std::string path;                               // the file, for errors found later
  std::map<std::string, std::string> segment_of;  // joint name -> one of segment_keys()
};

// head, upper_trunk, middle_trunk, lower_trunk, then left_ and right_ with upper_arm, forearm,
// hand, thigh, shank, foot.
const std::vector<std::string>& segment_keys();

// The map in `text`; `path` names it in errors. Throws std::invalid_argument "<path>: ..." for
// text that is not a YAML map of names, a segment not in segment_keys(), a segment given twice.
SegmentMap parse_segment_map(const std::string& text, const std::string& path);

// parse_segment_map of the file at `path`; std::invalid_argument "<path>: cannot open".
SegmentMap read_segment_map(const std::string& path);

}  // namespace mbk
