// mbk bag's default estimator "auto" (estimation/auto_estimator.h) through OfflineStates and
// OfflineBatch: a coordinate in every row and one in every other row get accurate derivatives,
// and every thread count gives the same rows (the workers share the fits).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "mb_kinematics/offline/offline_batch.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/recording.h"

namespace {

double wave(double t, int d, double f) {  // sin(2 pi f t) and its derivatives
  const double w = 2 * M_PI * f;
  return d == 0 ? std::sin(w * t) : d == 1 ? w * std::cos(w * t) : -w * w * std::sin(w * t);
}

// J1 in every row at 1 kHz, J2 in every other row; optionally a NaN in J1 at row `bad`.
mbk::Recording recording(const mbk::Model& model, int rows, int bad) {
  mbk::RecordingBuilder b(model);
  for (int i = 0; i < rows; ++i) {
    const double t = 1e-3 * i;
    const double j1 = i == bad ? std::numeric_limits<double>::quiet_NaN() : wave(t, 0, 1.1);
    if (i % 2 == 0)
      b.add(t, {"J1", "J2"}, {j1, wave(t, 0, 0.7)}, {}, "s");
    else
      b.add(t, {"J1"}, {j1}, {}, "s");
  }
  return b.finish();
}

TEST(OfflineAutoTest, AccurateOnFullAndPartialCoordinates) {
  const mbk::Model model = mbk::make_bare_model({0, 1}, mbk::JointType::kRevolute);
  const mbk::Recording r = recording(model, 2000, -1);
  mbk::OfflineStates states(model, r, mbk::make_offline_estimator("auto"), 0);
  mbk::JointState<double> s(model);
  for (int row = 0; row < 2000; ++row) {
    ASSERT_EQ(states.state_at(row, s), "") << row;
    const double t = 1e-3 * row, t2 = 2e-3 * (row / 2);  // J2 holds its last own sample
    EXPECT_NEAR(s.velocity[0], wave(t, 1, 1.1), 1e-8) << row;
    EXPECT_NEAR(s.acceleration[0], wave(t, 2, 1.1), 1e-5) << row;
    EXPECT_NEAR(s.velocity[1], wave(t2, 1, 0.7), 1e-8) << row;
    EXPECT_NEAR(s.acceleration[1], wave(t2, 2, 0.7), 1e-5) << row;
  }
}

// The error bars of a coordinate with known noise: its level, and standard errors that grow
// with the derivative's order.
TEST(OfflineAutoTest, ErrorSummaryGivesTheNoiseLevel) {
  const mbk::Model model = mbk::make_bare_model({0, 1}, mbk::JointType::kRevolute);
  mbk::RecordingBuilder b(model);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1e-3);
  for (int i = 0; i < 2000; ++i) {
    const double t = 1e-3 * i;
    b.add(t, {"J1", "J2"}, {wave(t, 0, 1.1) + noise(rng), wave(t, 0, 0.7)}, {}, "s");
  }
  const mbk::Recording r = b.finish();
  const mbk::OfflineStates states(model, r, mbk::make_offline_estimator("auto"), 0);
  const std::vector<mbk::CoordinateError> errors = states.error_summary();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].name, "J1");
  EXPECT_NEAR(errors[0].noise, 1e-3, 1e-4);
  EXPECT_GT(errors[0].acceleration_se, errors[0].velocity_se);
  EXPECT_GT(errors[0].velocity_se, 0);
  EXPECT_LT(errors[1].noise, 1e-9);  // clean
  EXPECT_TRUE(mbk::OfflineStates(model, r, mbk::make_offline_estimator("centered_9_4"), 0)
                  .error_summary()
                  .empty());
}

TEST(OfflineAutoTest, EveryThreadCountGivesTheSameRows) {
  const mbk::Model model = mbk::make_bare_model({0, 1}, mbk::JointType::kRevolute);
  const mbk::Recording rec = recording(model, 600, 300);  // the builder drops the NaN sample
  const int rows = rec.rows();
  ASSERT_EQ(rows, 599);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("auto");
  std::vector<std::vector<mbk::OfflineRow>> results;
  for (int threads : {1, 3}) {
    mbk::OfflineBatch batch(model, rec, e, 0, nullptr, threads);
    std::vector<mbk::OfflineRow> out(rows, mbk::OfflineRow(model));
    batch.start(0, rows, out);
    batch.finish();
    results.push_back(out);
  }
  for (int r = 0; r < rows; ++r) {
    ASSERT_EQ(results[0][r].drop_reason, "") << r;
    EXPECT_EQ(results[1][r].drop_reason, "") << r;
    EXPECT_EQ(results[0][r].state.acceleration, results[1][r].state.acceleration) << r;
  }
}

}  // namespace
