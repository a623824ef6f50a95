// recording_states (offline/recording_states.h): a recording's states in memory are those mbk
// bag computes (bvh_frame_state, mbk eval --frame's state of a BVH frame, is mbk bag's for that
// frame), with standard errors for "auto"; arrays make the same recording as a file.
#include "mb_kinematics/offline/recording_states.h"

#include <gtest/gtest.h>

#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/offline/bvh_recording.h"
#include "test/support/test_models.h"

namespace {

constexpr double kScale = 0.056444;

TEST(RecordingStates, BvhFramesAreMbkBags) {
  const std::string path = mbk_test::source_path("test/mocap/131_01.bvh");
  const mbk::BvhFile bvh = mbk::read_bvh(path);
  mbk::BvhModelOptions options;
  options.scale = kScale;
  const mbk::Model model = mbk::model_from_bvh(bvh, options);
  mbk::DropLog log;
  const mbk::Recording recording = mbk::read_recording_file(model, path, kScale, log);
  for (const std::string estimator : {"auto", "centered_9_4"}) {
    const mbk::RecordingStates s = mbk::recording_states(model, recording, estimator);
    ASSERT_EQ(static_cast<std::size_t>(recording.rows()), s.drop_reason.size());
    EXPECT_EQ(estimator == "auto", !s.velocity_se.empty());
    for (int frame : {0, 1, 400, recording.rows() - 1}) {
      const mbk::JointState<double> expected =
          mbk::bvh_frame_state(bvh, model, kScale, frame, estimator);
      EXPECT_EQ("", s.drop_reason[frame]);
      for (int c = 0; c < model.nq; ++c) {
        const std::size_t at = static_cast<std::size_t>(frame) * model.nq + c;
        ASSERT_EQ(expected.position[c], s.position[at]) << estimator << " " << frame << " " << c;
        ASSERT_EQ(expected.velocity[c], s.velocity[at]) << estimator << " " << frame << " " << c;
        ASSERT_EQ(expected.acceleration[c], s.acceleration[at]) << estimator << " " << frame;
      }
    }
  }
}

TEST(RecordingStates, ArraysAsARecording) {
  const mbk::Model model = mbk_test::revolute_chain(3);
  const double t[] = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  std::vector<double> q(7 * 3);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = 0.01 * i * i;
  const mbk::Recording r = mbk::recording_of_positions(3, 7, t, q.data());
  const mbk::RecordingStates s = mbk::recording_states(model, r, "centered_5_2");
  // q_c(row) = 0.01 (3 row + c)^2: a quadratic in t, which a quadratic fit differentiates exactly.
  for (int row = 0; row < 7; ++row)
    for (int c = 0; c < 3; ++c) {
      const double x = 3 * row + c;
      EXPECT_NEAR(0.01 * 2 * x * 3 / 0.1, s.velocity[row * 3 + c], 1e-9) << row << " " << c;
      EXPECT_NEAR(0.01 * 2 * 9 / 0.01, s.acceleration[row * 3 + c], 1e-7) << row << " " << c;
    }
  const double back[] = {0, 0.1, 0.1};
  EXPECT_THROW(mbk::recording_of_positions(3, 3, back, q.data()), std::invalid_argument);
  EXPECT_THROW(mbk::recording_states(model, r, "median"), std::invalid_argument);
}

}  // namespace
