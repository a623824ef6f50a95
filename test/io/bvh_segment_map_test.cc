// The user's map of BVH joints to segments (mb_kinematics/io/bvh_segment_map.h): what it reads
// and the one-line errors for what it refuses.
#include "mb_kinematics/io/bvh_segment_map.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace {

std::string error_of(const std::string& text) {
  try {
    mbk::parse_segment_map(text, "map.yaml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << text;
  return "";
}

TEST(SegmentMap, ReadsJointNamesToSegments) {
  const mbk::SegmentMap map =
      mbk::parse_segment_map("Bone_07: left_thigh\n\"mixamorig:Hd\": head\n", "map.yaml");
  EXPECT_EQ(map.path, "map.yaml");
  ASSERT_EQ(map.segment_of.size(), 2u);
  EXPECT_EQ(map.segment_of.at("Bone_07"), "left_thigh");
  EXPECT_EQ(map.segment_of.at("mixamorig:Hd"), "head");
  EXPECT_EQ(mbk::segment_keys().size(), 16u);
}

TEST(SegmentMap, RefusesWhatIsNotAMapOfKnownSegmentsEachOnce) {
  EXPECT_EQ(error_of("- a\n- b\n"), "map.yaml: expected a map of joint name: segment");
  EXPECT_EQ(
      error_of("Bone: tail\n").rfind("map.yaml: joint Bone: 'tail' is not a segment (head, ", 0),
      0u);
  EXPECT_EQ(error_of("A: head\nB: head\n"), "map.yaml: head given to two joints, A and B");
  EXPECT_EQ(error_of("A: [head]\n"), "map.yaml:1: expected joint name: segment");
  EXPECT_EQ(error_of("A: {\n").rfind("map.yaml: not YAML: ", 0), 0u);
}

}  // namespace
