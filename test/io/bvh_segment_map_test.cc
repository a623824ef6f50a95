// The user's map of BVH joints to segments (mb_kinematics/io/bvh_segment_map.h): what it reads,
// the one-line errors for what it refuses, and that it can say all the naming rules say: CMU's
// walk with every joint renamed, mapped to the joints the rules find, has the rules' masses and
// whole-body mass center.
#include "mb_kinematics/io/bvh_segment_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"
#include "test/support/test_models.h"

namespace {

constexpr double kScale = 0.0254 / 0.45;  // CMU's unit, test/mocap/README.md
constexpr double kMass = 68.5;

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
  ASSERT_EQ(map.segment.size(), 2u);
  EXPECT_EQ(map.segment.at("left_thigh").joint, "Bone_07");
  EXPECT_FALSE(map.segment.at("left_thigh").proximal);
  EXPECT_EQ(map.segment.at("head").joint, "mixamorig:Hd");
  EXPECT_EQ(mbk::segment_keys().size(), 16u);
}

TEST(SegmentMap, ReadsEachSegmentsJointAndEnds) {
  const mbk::SegmentMap map = mbk::parse_segment_map(
      "head: {joint: B3, distal: B2}\n"
      "left_foot: {joint: B9, distal: {end_site: B10}}\n"
      "lower_trunk: {joint: B0, distal: [B7, B11]}\n"
      "upper_trunk:\n  proximal: B2\n",
      "map.yaml");
  ASSERT_EQ(map.segment.size(), 4u);
  const mbk::MappedSegment& head = map.segment.at("head");
  EXPECT_EQ(head.joint, "B3");
  EXPECT_FALSE(head.proximal);
  ASSERT_TRUE(head.distal);
  EXPECT_EQ(head.distal->joints, std::vector<std::string>{"B2"});
  EXPECT_FALSE(head.distal->end_site);
  const mbk::MappedSegment& foot = map.segment.at("left_foot");
  EXPECT_EQ(foot.distal->joints, std::vector<std::string>{"B10"});
  EXPECT_TRUE(foot.distal->end_site);
  EXPECT_EQ(map.segment.at("lower_trunk").distal->joints, (std::vector<std::string>{"B7", "B11"}));
  EXPECT_EQ(map.segment.at("upper_trunk").joint, "");
  EXPECT_EQ(map.segment.at("upper_trunk").proximal->joints, std::vector<std::string>{"B2"});
}

TEST(SegmentMap, RefusesWhatIsNotAMapOfKnownSegmentsEachOnce) {
  EXPECT_EQ(error_of("- a\n- b\n"), "map.yaml: expected a map of joint name: segment");
  EXPECT_EQ(
      error_of("Bone: tail\n").rfind("map.yaml: joint Bone: 'tail' is not a segment (head, ", 0),
      0u);
  EXPECT_EQ(error_of("tail: {joint: A}\n").rfind("map.yaml: 'tail' is not a segment (head, ", 0),
            0u);
  EXPECT_EQ(error_of("A: head\nB: head\n"), "map.yaml: head given to two joints, A and B");
  EXPECT_EQ(error_of("A: head\nhead: {joint: B}\n"),
            "map.yaml: head given to two joints, A and the entry at line 2");
  EXPECT_EQ(error_of("A: [head]\n"),
            "map.yaml:1: expected joint name: segment, or segment: {joint: ...}");
  EXPECT_EQ(error_of("A: {\n").rfind("map.yaml: not YAML: ", 0), 0u);
  EXPECT_EQ(error_of("head: {joint: A, top: B}\n"),
            "map.yaml:1: head: 'top' is not a field (joint, proximal, distal)");
  EXPECT_EQ(error_of("head: {joint: [A, B]}\n"), "map.yaml:1: head: joint: expected a joint name");
  EXPECT_EQ(error_of("head: {distal: {tip: A}}\n"),
            "map.yaml:1: head: distal: expected a joint name, a list of them or {end_site: NAME}");
  EXPECT_EQ(error_of("middle_trunk: {proximal: A}\n"),
            "map.yaml:1: middle_trunk: its proximal end is placed by the table's trunk part "
            "lengths (give upper_trunk's proximal, SUPR, and lower_trunk's distal, MIDH)");
  EXPECT_EQ(error_of("upper_trunk: {distal: A}\n").rfind("map.yaml:1: upper_trunk: its distal", 0),
            0u);
}

// test/mocap/131_01.bvh with every ROOT and JOINT named Bone<i> (i from 0, file order): no
// naming rule finds a segment in it. `bone` gets each original name's new one.
std::string anonymous(const std::string& text, std::unordered_map<std::string, std::string>& bone) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (const char* keyword : {"ROOT ", "JOINT "}) {
      const size_t at = line.find(keyword);
      if (at == std::string::npos) continue;
      const size_t name = at + std::string(keyword).size();
      const std::string renamed = "Bone" + std::to_string(bone.size());
      bone[line.substr(name)] = renamed;
      line = line.substr(0, name) + renamed;
    }
    out += line + "\n";
  }
  return out;
}

// The whole-body mass center of every 10th frame.
std::vector<mbk::Vec3<double>> mass_centers(const mbk::BvhFile& bvh, const mbk::Model& model) {
  std::vector<mbk::Vec3<double>> out;
  mbk::JointState<double> state(model);
  mbk::Data<double> data(model);
  mbk::SystemKinematics<double> system;
  for (int f = 0; f < bvh.frame_count; f += 10) {
    const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, model, f, kScale);
    state.position = Eigen::Map<const Eigen::VectorXd>(q.data(), q.size());
    mbk::forward_kinematics(model, state, data, mbk::Level::kPose);
    mbk::system_kinematics(model, data, system, mbk::Level::kPose);
    out.push_back(system.mass_center);
  }
  return out;
}

double largest_difference(const std::vector<mbk::Vec3<double>>& a,
                          const std::vector<mbk::Vec3<double>>& b) {
  double most = 0;
  for (size_t i = 0; i < a.size(); ++i) most = std::max(most, (a[i] - b[i]).norm());
  return most;
}

mbk::Model with_map(const mbk::BvhFile& bvh, const std::string& yaml, const std::string& name) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << yaml;
  mbk::BvhModelOptions options{kScale, kMass, "male"};
  options.segments = path;
  return mbk::model_from_bvh(bvh, options);
}

// A map naming the joints the rules find (each limb's joint; the head with C7 at the neck joint;
// the trunk's parts on the spine bodies the rules choose, between SUPR at C7 and MIDH between the
// hips) gives the rules' segments on a skeleton whose names no rule knows: the same masses and
// whole-body mass center in every frame, to 1e-9 m (summation order aside, they are the same
// numbers). Without C7 (the head alone) the head reaches down to its own joint.
TEST(SegmentMap, AMapNamingTheRulesJointsGivesTheRulesMassCenter) {
  const std::string path = mbk_test::source_path("test/mocap/131_01.bvh");
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  std::unordered_map<std::string, std::string> b;
  const mbk::BvhFile named = mbk::parse_bvh(text.str(), "131_01.bvh");
  const mbk::BvhFile bones = mbk::parse_bvh(anonymous(text.str(), b), "bones.bvh");
  const mbk::Model rules = mbk::model_from_bvh(named, {kScale, kMass, "male"});
  ASSERT_TRUE(rules.warnings.empty()) << rules.warnings.front();
  // 131_01's names (Biovision's): the thigh LeftHip, shank LeftKnee, foot LeftAnkle, upper arm
  // LeftShoulder, forearm LeftElbow, hand LeftWrist; C7 at lowerneck; the trunk's lower, middle
  // and upper parts on Hips, lowerback and Chest, as the rules place them.
  const std::vector<std::pair<std::string, std::string>> parts = {
      {"Hip", "thigh"},          {"Knee", "shank"},    {"Ankle", "foot"},
      {"Shoulder", "upper_arm"}, {"Elbow", "forearm"}, {"Wrist", "hand"}};
  std::string limbs;
  for (const std::string side : {"left", "right"})
    for (const auto& [joint, segment] : parts)
      limbs += side + "_" + segment +
               ": {joint: " + b[(side == "left" ? "Left" : "Right") + joint] + "}\n";
  const std::string head = "head: {joint: " + b["Head"] + ", distal: " + b["lowerneck"] + "}\n";
  const std::string trunk = "upper_trunk: {joint: " + b["Chest"] + ", proximal: " + b["lowerneck"] +
                            "}\nmiddle_trunk: {joint: " + b["lowerback"] +
                            "}\nlower_trunk: {joint: " + b["Hips"] + ", distal: [" + b["LeftHip"] +
                            ", " + b["RightHip"] + "]}\n";
  const mbk::Model mapped = with_map(bones, limbs + head + trunk, "bones_full.yaml");
  EXPECT_TRUE(mapped.warnings.empty()) << mapped.warnings.front();
  for (int k = 1; k <= rules.body_count(); ++k) {
    EXPECT_NEAR(mapped.bodies[k].mass, rules.bodies[k].mass, 1e-12 * kMass) << rules.bodies[k].name;
    EXPECT_LT((mapped.bodies[k].mass_center - rules.bodies[k].mass_center).norm(), 1e-12)
        << rules.bodies[k].name;
  }
  EXPECT_LT(largest_difference(mass_centers(named, rules), mass_centers(bones, mapped)), 1e-9);
  // The joints alone, without C7: CERV falls to the head's own joint, the trunk reaches up to it.
  const mbk::Model joints_only =
      with_map(bones, limbs + "head: {joint: " + b["Head"] + "}\n", "bones_joints.yaml");
  EXPECT_GT(largest_difference(mass_centers(named, rules), mass_centers(bones, joints_only)), 1e-3);
}

}  // namespace
