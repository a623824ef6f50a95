// A user's map from a BVH skeleton's joints to the anthropometric table's segments
// (`--segments FILE`, doc/anthropometry.md#a-map-of-your-own), for skeletons whose names the
// naming rules miss: a YAML map that can say all the rules say, per segment the joint that
// carries it and its proximal and distal ends (the neck's C7 as the head's distal end). ROS-free.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mbk {

// A point of the rest pose: the origin of one joint, the mean of several joints' origins (MIDH
// between the hips), or the End Site of one joint.
struct MapPoint {
  std::vector<std::string> joints;
  bool end_site = false;  // the End Site of joints[0]
};

// One segment of the map: the joint that carries it ("": the rules' body) and its ends (none:
// the rules' ends on that body).
struct MappedSegment {
  std::string joint;
  std::optional<MapPoint> proximal, distal;
  int line = 0;  // in the map's file, for errors found later
};

struct SegmentMap {
  std::string path;                              // the file, for errors found later
  std::map<std::string, MappedSegment> segment;  // segment key (segment_keys()) -> its entry
};

// head, upper_trunk, middle_trunk, lower_trunk, then left_ and right_ with upper_arm, forearm,
// hand, thigh, shank, foot.
const std::vector<std::string>& segment_keys();

// The map in `text`; `path` names it in errors. Two forms of entry, mixed at will:
//   Bone_07: left_thigh                      joint name: segment (the joint carries it)
//   left_foot: {joint: Bone_09, proximal: Bone_09, distal: {end_site: Bone_10}}
//   head: {joint: Bone_03, distal: Bone_02}  (distal: CERV, the neck's C7)
// A point is a joint name (its origin), a list of names (the mean of their origins) or
// {end_site: NAME}. The trunk's ends are SUPR (upper_trunk's proximal) and MIDH (lower_trunk's
// distal); XYPH and OMPH follow from the table. Throws std::invalid_argument "<path>[:line]: ..."
// for text that is not such a map, a segment not in segment_keys(), a segment given twice, a
// field other than joint, proximal, distal, an end the table places itself (upper_trunk's
// distal, middle_trunk's, lower_trunk's proximal).
SegmentMap parse_segment_map(const std::string& text, const std::string& path);

// parse_segment_map of the file at `path`; std::invalid_argument "<path>: cannot open".
SegmentMap read_segment_map(const std::string& path);

}  // namespace mbk
