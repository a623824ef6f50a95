// The zero-phase offline estimator (estimation/offline_estimator.h): exact on polynomials of its
// order at every sample, ends and gaps included; centred where it can be; what it refuses.
#include "mb_kinematics/estimation/offline_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace {

// Irregular stamps at about `rate` Hz over `seconds`, with a gap of `gap` s after the middle.
std::vector<double> stamps(double rate, double seconds, double gap) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<double> t;
  const int n = static_cast<int>(rate * seconds);
  for (int i = 0; i < n; ++i) t.push_back((i + u(rng)) / rate + (i >= n / 2 ? gap : 0.0));
  return t;
}

double cubic(double t, int order) {
  if (order == 0) return 0.3 - 1.2 * t + 0.8 * t * t - 0.45 * t * t * t;
  if (order == 1) return -1.2 + 1.6 * t - 1.35 * t * t;
  return 1.6 - 2.7 * t;
}

TEST(OfflineEstimatorTest, ExactOnCubicsEverywhere) {
  for (const std::string& name : mbk::offline_estimator_names()) {
    const mbk::OfflineEstimator e = mbk::make_offline_estimator(name);
    if (e.order < 3) continue;
    const std::vector<double> t = stamps(100, 2.0, 0.5);
    std::vector<double> x, first, second;
    std::vector<int> valid;
    for (double s : t) x.push_back(cubic(s, 0));
    mbk::estimate_offline(e, t, x, 0.1, first, second, valid);
    for (size_t i = 0; i < t.size(); ++i) {
      ASSERT_EQ(valid[i], 2) << name << " sample " << i;
      EXPECT_NEAR(first[i], cubic(t[i], 1), 1e-9) << name << " sample " << i;
      EXPECT_NEAR(second[i], cubic(t[i], 2), 1e-7) << name << " sample " << i;
    }
  }
}

TEST(OfflineEstimatorTest, CentredInsideOneSidedAtEndsAndGaps) {
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_9_4");
  const std::vector<double> t = stamps(100, 2.0, 0.5);  // 100 + 100 samples, a 0.5 s gap
  const mbk::Segments s = mbk::find_segments(t, 0.1);
  ASSERT_EQ(s.begin.size(), 2u);
  EXPECT_EQ(s.end[0], 100);
  mbk::DerivativeWeights w;
  mbk::derivative_weights(e, t, s, 50, w);  // inside: 4 samples on each side
  EXPECT_EQ(w.begin, 46);
  EXPECT_EQ(w.count, 9);
  mbk::derivative_weights(e, t, s, 1, w);  // start: shifted to one side
  EXPECT_EQ(w.begin, 0);
  mbk::derivative_weights(e, t, s, 98, w);  // before the gap: never across it
  EXPECT_EQ(w.begin + w.count, 100);
  mbk::derivative_weights(e, t, s, 101, w);  // after it
  EXPECT_EQ(w.begin, 100);
  // On uniform stamps the centred fit is antisymmetric in x' and symmetric in x''.
  std::vector<double> u;
  for (int i = 0; i < 30; ++i) u.push_back(0.01 * i);
  const mbk::Segments su = mbk::find_segments(u, 0);
  mbk::derivative_weights(e, u, su, 15, w);
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(w.first[j], -w.first[8 - j], 1e-9);
    EXPECT_NEAR(w.second[j], w.second[8 - j], 1e-6);
  }
}

TEST(OfflineEstimatorTest, TimeWindowScalesWithTheRate) {
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_0.1s_3");
  for (double rate : {100.0, 1000.0}) {
    std::vector<double> t;
    for (int i = 0; i < 2 * rate; ++i) t.push_back(i / rate);
    const mbk::Segments s = mbk::find_segments(t, 0);
    mbk::DerivativeWeights w;
    const int i = static_cast<int>(rate);
    mbk::derivative_weights(e, t, s, i, w);
    EXPECT_LE(w.count, mbk::kMaxOfflineWindow);
    EXPECT_EQ((i - w.begin) % w.stride, 0);  // the estimated sample is one of those fitted
    EXPECT_NEAR(t[w.row(w.count - 1)] - t[w.begin], 0.1, 1.5 * w.stride / rate) << rate;
    EXPECT_NEAR(t[i] - t[w.begin], 0.05, 1.5 * w.stride / rate) << rate;
  }
}

TEST(OfflineEstimatorTest, ShortRunsLowerTheOrderOrGiveNothing) {
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_9_4");
  const std::vector<double> t = {0.0, 0.01, 5.0, 5.01, 5.02, 9.0};  // runs of 2, 3 and 1
  const std::vector<double> x = {1.0, 1.02, 2.0, 2.01, 2.04, 3.0};
  std::vector<double> first, second;
  std::vector<int> valid;
  mbk::estimate_offline(e, t, x, 1.0, first, second, valid);
  EXPECT_EQ(valid, (std::vector<int>{1, 1, 2, 2, 2, 0}));
  EXPECT_NEAR(first[0], 2.0, 1e-9);     // the line through the two
  EXPECT_NEAR(second[3], 200.0, 1e-6);  // the parabola through the three
}

TEST(OfflineEstimatorTest, DefaultGapIsFiveMedianIntervals) {
  EXPECT_DOUBLE_EQ(mbk::default_max_gap({0.0, 0.01, 0.02, 0.03, 1.0}), 0.05);
  EXPECT_EQ(mbk::default_max_gap({1.0}), 0.0);
}

TEST(OfflineEstimatorTest, RefusesUnknownNamesAndBadSettings) {
  for (const char* bad : {"kalman", "centered_8_2", "centered_9_1", "centered_9_6", "centered_s_3",
                          "centered_-0.1s_3", "centered_9_4x"})
    EXPECT_THROW(mbk::make_offline_estimator(bad), std::invalid_argument) << bad;
  EXPECT_NO_THROW(mbk::make_offline_estimator(mbk::default_offline_estimator()));
}

}  // namespace
