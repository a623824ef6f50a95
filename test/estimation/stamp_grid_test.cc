// Stamps on a uniform grid to within their rounding (estimation/stamp_grid.h): a 1 kHz grid
// written through rospy.Time.from_sec is found and moved back onto the grid; gaps of whole
// periods keep it; stamps already exact are left alone; real jitter is never snapped.
#include "mb_kinematics/estimation/stamp_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

// t as a bag holds it when written with rospy.Time.from_sec (genpy's rostime.py: secs =
// int(t), nsecs = int((t - secs) * 1e9), both truncated) and read with ros::Time::toSec.
double rospy_stamp(double t) {
  const double secs = std::trunc(t), nsecs = std::trunc((t - secs) * 1e9);
  return secs + 1e-9 * nsecs;
}

std::vector<double> grid_times(double t0, double h, int n) {
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = t0 + i * h;
  return t;
}

TEST(StampGridTest, RoundedStampsGoBackOntoTheGrid) {
  const std::vector<double> exact = grid_times(10.0, 1e-3, 20000);
  std::vector<double> t = exact;
  for (double& x : t) x = rospy_stamp(x);
  double before = 0;
  for (size_t i = 0; i < t.size(); ++i) before = std::max(before, std::abs(t[i] - exact[i]));
  EXPECT_GT(before, 5e-10);  // the rounding is there
  const mbk::StampGrid grid = mbk::snap_to_stamp_grid(t);
  ASSERT_TRUE(grid.found);
  EXPECT_TRUE(grid.moves);
  EXPECT_NEAR(grid.period, 1e-3, 1e-14);
  EXPECT_LE(grid.worst, 1e-9);
  // On the grid up to one shift of every time (the rounding's mean, within 1 ns) and a drift of
  // a fraction of the rounding (the fitted period's error over 20 s).
  const double shift = t[0] - exact[0];
  EXPECT_LE(std::abs(shift), 1e-9);
  for (size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(t[i] - exact[i], shift, 2e-10) << i;
}

TEST(StampGridTest, GapsOfWholePeriodsKeepTheGrid) {
  std::vector<double> t;
  for (int i = 0; i < 5000; ++i)
    if (i % 97 != 5 && (i < 2000 || i > 2300)) t.push_back(rospy_stamp(3.0 + i * 2e-3));
  const mbk::StampGrid grid = mbk::snap_to_stamp_grid(t);
  ASSERT_TRUE(grid.found);
  EXPECT_NEAR(grid.period, 2e-3, 1e-14);
  const double shift = t[0] - 3.0;
  EXPECT_LE(std::abs(shift), 1e-9);
  for (double x : t) {
    const double k = std::round((x - 3.0) / 2e-3);
    ASSERT_NEAR(x - (3.0 + k * 2e-3), shift, 2e-10);
  }
}

TEST(StampGridTest, ExactStampsAreLeftAsTheyAre) {
  const std::vector<double> exact = grid_times(0.0, 1e-3, 20000);
  std::vector<double> t = exact;
  const mbk::StampGrid grid = mbk::snap_to_stamp_grid(t);
  EXPECT_TRUE(grid.found);
  EXPECT_FALSE(grid.moves);
  EXPECT_EQ(t, exact);
}

// Jitter far above the stamps' resolution is the recording's: never moved.
TEST(StampGridTest, JitteredStampsAreNotSnapped) {
  std::mt19937 rng(3);
  for (double jitter : {50e-6, 1e-6, 20e-9}) {
    std::uniform_real_distribution<double> noise(-jitter, jitter);
    std::vector<double> t = grid_times(5.0, 1e-3, 5000);
    for (double& x : t) x = rospy_stamp(x + noise(rng));
    const std::vector<double> before = t;
    const mbk::StampGrid grid = mbk::snap_to_stamp_grid(t);
    EXPECT_FALSE(grid.found) << jitter;
    EXPECT_FALSE(grid.moves) << jitter;
    EXPECT_EQ(t, before) << jitter;
  }
}

// Times written with 6 decimals at 120 Hz are up to 0.5 us off their grid: found when the
// tolerance allows the text's rounding, and a stamp a whole unit of the last decimal off a grid
// the decimals hold exactly is not on it.
TEST(StampGridTest, TextRoundingWidensTheTolerance) {
  std::vector<double> t = grid_times(1.0, 1.0 / 120, 1200);
  for (double& x : t) x = std::round(x * 1e6) / 1e6;
  EXPECT_FALSE(mbk::find_stamp_grid(t).found);
  const mbk::StampGrid grid = mbk::find_stamp_grid(t, 0.75e-6);
  EXPECT_TRUE(grid.found);
  EXPECT_TRUE(grid.moves);
  EXPECT_NEAR(grid.period, 1.0 / 120, 1e-12);
  std::vector<double> off = grid_times(1.0, 0.01, 1000);
  for (double& x : off) x = std::round(x * 1e3) / 1e3;
  EXPECT_TRUE(mbk::find_stamp_grid(off, 0.75e-3).found);
  off[500] += 1e-3;
  EXPECT_FALSE(mbk::find_stamp_grid(off, 0.75e-3).found);
}

// A first interval of 1e-20 s makes the next gap 1e20 periods, more than a count of periods holds
// (a fuzzer's stamps: test/fuzz/regressions/recording/; converting it to a long was undefined).
TEST(StampGridTest, GapsOfTooManyPeriodsHaveNoGrid) {
  EXPECT_FALSE(mbk::find_stamp_grid({0.0, 1e-20, 1.0, 2.0}).found);
  EXPECT_TRUE(mbk::find_stamp_grid({0.0, 1e-3, 2e-3, 1000.0, 1000.001}).found);  // 1e6 periods
}

TEST(StampGridTest, TooFewOrUnevenStampsHaveNoGrid) {
  EXPECT_FALSE(mbk::find_stamp_grid({}).found);
  EXPECT_FALSE(mbk::find_stamp_grid({1.0, 1.001}).found);
  EXPECT_FALSE(mbk::find_stamp_grid({1.0, 1.001, 1.0025, 1.0035}).found);  // half a period
}

}  // namespace
