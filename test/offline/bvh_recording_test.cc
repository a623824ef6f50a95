// A BVH file's motion as a recording (mb_kinematics/offline/bvh_recording.h): frames at their
// times, rotations unwrapped at +-180 degrees before they are differentiated, and a frame's
// state with the zero-phase estimator's derivatives (mbk eval --frame).
#include "mb_kinematics/offline/bvh_recording.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/io/bvh_model.h"
#include "test/support/test_models.h"

namespace {

constexpr double kScale = 0.01;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// test/io/data/cmu_walk.bvh: 40 frames at 1/60 s; the root's Zrotation is 170 + 40 t degrees
// written within +-180 (it wraps between frames 14 and 15), its Xposition 3 sin(2 t) cm.
mbk::BvhFile walk() { return mbk::read_bvh(mbk_test::source_path("test/io/data/cmu_walk.bvh")); }

TEST(BvhRecording, FramesAtTheirTimesWithUnwrappedAngles) {
  const mbk::BvhFile bvh = walk();
  const mbk::Model model = mbk::model_from_bvh(bvh, {kScale});
  mbk::RecordingBuilder builder(model);
  mbk::add_bvh_frames(bvh, model, kScale, builder);
  const mbk::Recording rec = builder.finish();
  ASSERT_EQ(rec.rows(), 40);
  EXPECT_EQ(builder.log().dropped(), 0);
  const int gamma = model.coordinate_index("Hips/gamma");
  for (int f = 0; f < 40; ++f) {
    EXPECT_NEAR(rec.stamp[f], (f + 1) * bvh.frame_time, 1e-15);
    EXPECT_NEAR(rec.position[f * rec.nq + gamma], (170 + 40 * f * bvh.frame_time) * kDeg, 1e-6)
        << "frame " << f;
  }
}

// Frames closer than a stamp's nanosecond (Frame Time 1e-12) are refused, naming the fix: they
// were all stamped 0.000000000.
TEST(BvhRecording, AFrameTimeBelowANanosecondIsRefused) {
  mbk::BvhFile bvh = walk();
  const mbk::Model model = mbk::model_from_bvh(bvh, {kScale});
  bvh.frame_time = 1e-12;
  mbk::RecordingBuilder builder(model);
  try {
    mbk::add_bvh_frames(bvh, model, kScale, builder);
    ADD_FAILURE() << "Frame Time 1e-12 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cmu_walk.bvh: Frame Time 1e-12 s is below 1 ns"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("correct the file's Frame Time"), std::string::npos);
  }
  bvh.frame_time = 1e-9;  // the finest a stamp holds
  EXPECT_NO_THROW(mbk::add_bvh_frames(bvh, model, kScale, builder));
}

TEST(BvhRecording, AFramesStateHasTheEstimatorsDerivatives) {
  const mbk::BvhFile bvh = walk();
  const mbk::Model model = mbk::model_from_bvh(bvh, {kScale});
  const mbk::JointState<double> s =
      mbk::bvh_frame_state(bvh, model, kScale, 15, mbk::default_offline_estimator());
  mbk::BvhFile unwrapped = bvh;  // frame 15's -180 degrees is 180 after frame 14's 179.33
  mbk::unwrap_rotations(unwrapped);
  const std::vector<double> q = mbk::bvh_frame_coordinates(unwrapped, model, 15, kScale);
  for (int i = 0; i < model.nq; ++i) EXPECT_EQ(s.position[i], q[i]) << i;
  const double t = 15 * bvh.frame_time;
  const int gamma = model.coordinate_index("Hips/gamma"), x = model.coordinate_index("Hips/x");
  EXPECT_NEAR(s.velocity[gamma], 40 * kDeg, 1e-3);  // across the wrap
  EXPECT_NEAR(s.acceleration[gamma], 0, 1e-2);
  EXPECT_NEAR(s.velocity[x], 0.06 * std::cos(2 * t), 1e-4);
  EXPECT_NEAR(s.acceleration[x], -0.12 * std::sin(2 * t), 1e-2);
  EXPECT_THROW(mbk::bvh_frame_state(bvh, model, kScale, 40, mbk::default_offline_estimator()),
               std::invalid_argument);
}

}  // namespace
