// BVH recordings of several families read as their exporters mean them: CMU's real walk
// (test/mocap) and synthetic walks in the exact layouts of Bandai Namco's dataset, LAFAN1 and
// Mixamo (test/mocap/synthetic: 6 channels per joint, _L/_R and mixamorig: names, a static
// root metres from the walker). Each has every mass-carrying segment, and a standing height
// (along y, up), a whole-body mass center height and a walking speed in a human's ranges, the
// mass center keeping up with the pelvis: the motion check says nothing.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/bvh_motion_check.h"
#include "test/support/test_models.h"

namespace {

struct Family {
  const char* path;
  double scale;  // metres per file unit
};

class BvhFamilies : public testing::TestWithParam<Family> {};

TEST_P(BvhFamilies, WalkAsAHumanWithEverySegmentFound) {
  const Family family = GetParam();
  const mbk::BvhFile bvh = mbk::read_bvh(mbk_test::source_path(family.path));
  const mbk::BvhModelOptions options{family.scale, 70.0, "male"};
  const mbk::Model model = mbk::model_from_bvh(bvh, options);
  EXPECT_TRUE(mbk::bvh_missing_segments(bvh, options).empty());
  for (const std::string& warning : model.warnings)
    EXPECT_EQ(warning.find("incomplete"), std::string::npos) << warning;
  const mbk::MotionFigures m = mbk::motion_figures(bvh, model, family.scale);
  EXPECT_EQ(m.up, 1);        // y up, as all these files
  EXPECT_GT(m.height, 1.2);  // the joints' extent: to the head joint, not its top
  EXPECT_LT(m.height, 2.0);
  EXPECT_NEAR(m.rest_height / m.height, 1.0, 0.1);  // standing at rest, position channels too
  EXPECT_GT(m.mass_center_height, 0.75);
  EXPECT_LT(m.mass_center_height, 1.2);
  EXPECT_GT(m.mass_center_speed, 0.3);  // walking, over the whole recording
  EXPECT_LT(m.mass_center_speed, 2.5);
  EXPECT_NEAR(m.mass_center_speed / m.root_speed, 1.0, 0.1);
  EXPECT_EQ(mbk::motion_warning(bvh, model, family.scale, ""), "");
}

// Bandai Namco's End Sites are at OFFSET 0 0 0: its hands, toes and head end at their joints.
// Said once, naming the joints and the segments; the hand's mass center is on the wrist.
TEST(BandaiLayout, EndSitesAtTheJointAreSaidOnce) {
  const mbk::BvhFile bvh =
      mbk::read_bvh(mbk_test::source_path("test/mocap/synthetic/bandai_layout_walk.bvh"));
  const mbk::Model model = mbk::model_from_bvh(bvh, {0.01, 70.0, "male"});
  int said = 0;
  for (const std::string& warning : model.warnings)
    if (warning.find("OFFSET 0 0 0") != std::string::npos) {
      ++said;
      EXPECT_EQ(warning, bvh.path +
                             ": End Sites at OFFSET 0 0 0 (Hand_L, Toes_L, Hand_R, Toes_R, Head): "
                             "left hand, left foot, right hand, right foot, head and neck end at "
                             "that joint, not at the body's tip, so their mass centers lie on the "
                             "joint or short of the tip (--segments FILE gives other ends, "
                             "doc/anthropometry.md)");
    }
  EXPECT_EQ(said, 1);
  const mbk::Body& hand = model.bodies[model.body_index("Hand_L")];
  EXPECT_GT(hand.mass, 0.0);
  EXPECT_LT(hand.mass_center.norm(), 1e-12) << hand.mass_center.transpose();
  // The other families' End Sites reach past their joints: nothing to say.
  for (const char* path : {"test/mocap/131_01.bvh", "test/mocap/synthetic/lafan1_layout_walk.bvh",
                           "test/mocap/synthetic/mixamo_layout_walk.bvh"})
    for (const std::string& warning :
         mbk::model_from_bvh(mbk::read_bvh(mbk_test::source_path(path)), {0.01, 70.0, "male"})
             .warnings)
      EXPECT_EQ(warning.find("OFFSET 0 0 0"), std::string::npos) << warning;
}

// LAFAN1's layout as a reader that adds a JOINT's position channels to its OFFSET writes it
// back: every JOINT's position channels twice its OFFSET, the skeleton twice as tall in its
// motion as at rest (the rest pose taking each position channel at its OFFSET, as the file means
// it). Said, with that likely cause.
TEST(Lafan1Layout, OffsetsCountedTwiceAreSaid) {
  std::ifstream file(mbk_test::source_path("test/mocap/synthetic/lafan1_layout_walk.bvh"));
  std::stringstream in;
  in << file.rdbuf();
  std::string text = in.str();
  const size_t frames = text.find('\n', text.find("Frame Time:")) + 1;
  std::istringstream rows(text.substr(frames));
  std::string doubled, row;
  while (std::getline(rows, row)) {
    std::istringstream values(row);
    double x = 0;
    for (int column = 0; values >> x; ++column)  // 6 channels a joint; the ROOT's first
      doubled += std::to_string(column >= 6 && column % 6 < 3 ? 2 * x : x) + " ";
    doubled += "\n";
  }
  const mbk::BvhFile bvh = mbk::parse_bvh(text.substr(0, frames) + doubled, "twice.bvh");
  const mbk::Model model = mbk::model_from_bvh(bvh, {0.01, 70.0, "male"});
  const mbk::MotionFigures m = mbk::motion_figures(bvh, model, 0.01);
  EXPECT_NEAR(m.height / m.rest_height, 2.0, 0.2);
  const std::string warning = mbk::motion_warning(bvh, model, 0.01, "");
  EXPECT_EQ(warning.rfind("twice.bvh: the skeleton is ", 0), 0u) << warning;
  EXPECT_NE(warning.find("as when OFFSETs are counted twice"), std::string::npos) << warning;
}

INSTANTIATE_TEST_SUITE_P(
    Recordings, BvhFamilies,
    testing::Values(Family{"test/mocap/131_01.bvh", 0.0254 / 0.45},
                    Family{"test/mocap/synthetic/bandai_layout_walk.bvh", 0.01},
                    Family{"test/mocap/synthetic/lafan1_layout_walk.bvh", 0.01},
                    Family{"test/mocap/synthetic/mixamo_layout_walk.bvh", 0.01}));

}  // namespace
