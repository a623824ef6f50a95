// BVH recordings of several families read as their exporters mean them: CMU's real walk
// (test/mocap) and synthetic walks in the exact layouts of Bandai Namco's dataset, LAFAN1 and
// Mixamo (test/mocap/synthetic: 6 channels per joint, _L/_R and mixamorig: names, a static
// root metres from the walker). Each has every mass-carrying segment, and a standing height
// (along y, up), a whole-body mass center height and a walking speed in a human's ranges, the
// mass center keeping up with the pelvis: the motion check says nothing.
#include <gtest/gtest.h>

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
  EXPECT_EQ(m.up, 1);  // y up, as all these files
  EXPECT_GT(m.height, 1.2);  // the joints' extent: to the head joint, not its top
  EXPECT_LT(m.height, 2.0);
  EXPECT_GT(m.mass_center_height, 0.75);
  EXPECT_LT(m.mass_center_height, 1.2);
  EXPECT_GT(m.mass_center_speed, 0.3);  // walking, over the whole recording
  EXPECT_LT(m.mass_center_speed, 2.5);
  EXPECT_NEAR(m.mass_center_speed / m.root_speed, 1.0, 0.1);
  EXPECT_EQ(mbk::motion_warning(bvh, model, family.scale, ""), "");
}

INSTANTIATE_TEST_SUITE_P(
    Recordings, BvhFamilies,
    testing::Values(Family{"test/mocap/131_01.bvh", 0.0254 / 0.45},
                    Family{"test/mocap/synthetic/bandai_layout_walk.bvh", 0.01},
                    Family{"test/mocap/synthetic/lafan1_layout_walk.bvh", 0.01},
                    Family{"test/mocap/synthetic/mixamo_layout_walk.bvh", 0.01}));

}  // namespace
