// Body accelerations of a recording sampled on an exact 1 kHz grid whose stamps were rounded to
// nanoseconds as rospy.Time.from_sec rounds them: read through RecordingBuilder (which moves
// stamps on a grid back onto it, estimation/stamp_grid.h), "auto" gives them as on exact times;
// the rounded stamps taken as they are would not. A jittered recording keeps its stamps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/recording.h"
#include "mb_kinematics/offline/recording_states.h"

namespace {

constexpr int kBodies = 12, kRows = 2000;
constexpr double kStart = 10.0, kPeriod = 1e-3;

// genpy's rostime.py: from_sec(t) keeps int(t) s and int((t - int(t)) * 1e9) ns (truncated);
// ros::Time::toSec reads them back.
double rospy_stamp(double t) {
  const double secs = std::trunc(t), nsecs = std::trunc((t - secs) * 1e9);
  return secs + 1e-9 * nsecs;
}

// Coordinate c: sin(w_c t + c) with w_c from 1 to 6 rad/s; d: the derivative's order.
double motion(int c, double t, int d) {
  const double w = 1.0 + 5.0 * c / (kBodies - 1), x = w * t + c;
  return d == 0 ? std::sin(x) : d == 1 ? w * std::cos(x) : -w * w * std::sin(x);
}

mbk::JointState<double> exact_state(const mbk::Model& model, double t) {
  mbk::JointState<double> s(model);
  for (int c = 0; c < model.nq; ++c)
    s.position[c] = motion(c, t, 0), s.velocity[c] = motion(c, t, 1),
    s.acceleration[c] = motion(c, t, 2);
  return s;
}

// The largest error of the bodies' angular and mass-center accelerations over the rows, relative
// to the largest of those accelerations.
double body_acceleration_error(const mbk::Model& model, const mbk::Recording& rec,
                               double start = kStart) {
  mbk::OfflineStates states(model, rec, mbk::make_offline_estimator("auto"), 0);
  mbk::JointState<double> estimated(model);
  mbk::Data<double> got(model), want(model);
  double error = 0, scale = 0;
  for (int r = 0; r < rec.rows(); ++r) {
    EXPECT_EQ(states.state_at(r, estimated), "") << r;
    mbk::forward_kinematics(model, estimated, got, mbk::Level::kAcceleration);
    mbk::forward_kinematics(model, exact_state(model, start + r * kPeriod), want,
                            mbk::Level::kAcceleration);
    for (int k = 1; k <= kBodies; ++k) {
      error =
          std::max({error, (got.alpha[k] - want.alpha[k]).norm(),
                    (got.mass_center_acceleration[k] - want.mass_center_acceleration[k]).norm()});
      scale = std::max({scale, want.alpha[k].norm(), want.mass_center_acceleration[k].norm()});
    }
  }
  return error / scale;
}

// The recording through RecordingBuilder, as mbk bag reads it; `stamp[i]` for sample i, the
// motion at start + i kPeriod.
mbk::Recording read(const mbk::Model& model, const std::vector<double>& stamp,
                    double start = kStart) {
  mbk::RecordingBuilder builder(model);
  std::vector<double> q(model.nq);
  for (int i = 0; i < kRows; ++i) {
    for (int c = 0; c < model.nq; ++c) q[c] = motion(c, start + i * kPeriod, 0);
    builder.add(stamp[i], model.coordinate_names, q, {}, "sample " + std::to_string(i));
  }
  return builder.finish();
}

TEST(StampRoundingTest, BodyAccelerationsSeeThroughNanosecondStamps) {
  const mbk::Model model = mbk::make_random_revolute_tree(kBodies, 12);
  ASSERT_EQ(model.nq, kBodies);
  std::vector<double> stamp(kRows);
  for (int i = 0; i < kRows; ++i) stamp[i] = rospy_stamp(kStart + i * kPeriod);
  const mbk::Recording rec = read(model, stamp);
  ASSERT_TRUE(rec.grid.moves);
  EXPECT_NEAR(rec.grid.period, kPeriod, 1e-13);
  const double on_grid = body_acceleration_error(model, rec);
  // As good as on the exact times (the rounding's mean shifts every time by under 1 ns).
  std::vector<double> exact(kRows);
  for (int i = 0; i < kRows; ++i) exact[i] = kStart + i * kPeriod;
  const double on_exact = body_acceleration_error(
      model, mbk::recording_of_positions(model.nq, kRows, exact.data(), rec.position.data()));
  EXPECT_LT(on_grid, 1e-5);
  EXPECT_LT(on_grid, 2 * on_exact);
  EXPECT_EQ(rec.recorded_stamp, stamp);  // the outputs' times
  // The same positions at the rounded stamps as they are: the rounding dominates.
  mbk::Recording as_stamped = rec;
  as_stamped.stamp = stamp;
  as_stamped.grid = mbk::StampGrid();  // no grid: the offsets are the stamps' differences
  const double rounded = body_acceleration_error(model, as_stamped);
  EXPECT_GT(rounded, 100 * on_grid);
  char figures[128];
  std::snprintf(figures, sizeof figures,
                "%.2e on the grid, %.2e on exact times, %.2e at the stamps", on_grid, on_exact,
                rounded);
  RecordProperty("relative_body_acceleration_error", figures);
}

// A bag stamped by a wall clock (1.7e9 s, where doubles lie 2.4e-7 s apart): its stamps in double
// seconds are not moved (no grid time is nearer in double), but on their grid the offsets within
// each window are whole periods, so the accelerations are as on exact times; the stamps'
// differences as they are would give 2.4e-7 s of noise per 1 ms.
TEST(StampRoundingTest, WallClockStampsOnAGridGiveExactOffsets) {
  const mbk::Model model = mbk::make_random_revolute_tree(kBodies, 12);
  std::vector<double> stamp(kRows), exact(kRows);
  for (int i = 0; i < kRows; ++i)  // ros::Time(1700000000, i ms).toSec()
    stamp[i] = 1700000000.0 + 1e-9 * (i * 1000000.0), exact[i] = kStart + i * kPeriod;
  const mbk::Recording rec = read(model, stamp, kStart);
  ASSERT_TRUE(rec.grid.found);
  EXPECT_FALSE(rec.grid.moves);
  const double on_grid = body_acceleration_error(model, rec);
  const double on_exact = body_acceleration_error(
      model, mbk::recording_of_positions(model.nq, kRows, exact.data(), rec.position.data()));
  EXPECT_LT(on_grid, 1e-5);
  EXPECT_LT(on_grid, 2 * on_exact);
  mbk::Recording as_stamped = rec;
  as_stamped.grid = mbk::StampGrid();
  const double rounded = body_acceleration_error(model, as_stamped);
  EXPECT_GT(rounded, 100 * on_grid);
  char figures[128];
  std::snprintf(figures, sizeof figures,
                "%.2e on the grid, %.2e on exact times, %.2e at the stamps' differences", on_grid,
                on_exact, rounded);
  RecordProperty("relative_body_acceleration_error", figures);
}

TEST(StampRoundingTest, JitteredStampsAreKept) {
  const mbk::Model model = mbk::make_random_revolute_tree(kBodies, 12);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-50e-6, 50e-6);
  std::vector<double> stamp(kRows);
  for (int i = 0; i < kRows; ++i) stamp[i] = rospy_stamp(kStart + i * kPeriod + jitter(rng));
  const mbk::Recording rec = read(model, stamp);
  EXPECT_FALSE(rec.grid.found);
  EXPECT_EQ(rec.stamp, stamp);
  EXPECT_TRUE(rec.recorded_stamp.empty());
}

}  // namespace
