// The zero-phase offline estimator (estimation/offline_estimator.h): exact on polynomials of its
// order at every sample, ends and gaps included; centred where it can be; what it refuses.
#include "mb_kinematics/estimation/offline_estimator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>

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

// A bag's stamps at 1 kHz from t0 s on: whole seconds and nanoseconds, read as ros::Time::toSec
// does (sec + 1e-9 nsec in double).
std::vector<double> bag_stamps(long t0, int n) {
  std::vector<double> t;
  for (int k = 0; k < n; ++k) {
    const long ns = t0 * 1000000000L + k * 1000000L;
    t.push_back(static_cast<double>(ns / 1000000000L) +
                1e-9 * static_cast<double>(ns % 1000000000L));
  }
  return t;
}

// Whole-nanosecond stamps far from 0 (1000 s: doubles 1.1e-13 s apart) are not equally spaced in
// double; their offsets are taken in whole nanoseconds, so every centred window has the same
// weights, Savitzky and Golay's for 5 samples at order 3: x' (1, -8, 0, 8, -1) / 12h and
// x'' (2, -1, -2, -1, 2) / 7h^2, to the last few bits.
TEST(OfflineEstimatorTest, WholeNanosecondStampsGiveExactOffsets) {
  const std::vector<double> t = bag_stamps(1000, 200);
  std::vector<double> steps;
  for (int i = 1; i < 20; ++i) steps.push_back(t[i] - t[i - 1]);
  ASSERT_NE(*std::min_element(steps.begin(), steps.end()),
            *std::max_element(steps.begin(), steps.end()));  // unequal in double
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_5_3");
  const mbk::Segments s = mbk::find_segments(t, 0);
  const double h = 1e-3, first[5] = {1, -8, 0, 8, -1}, second[5] = {2, -1, -2, -1, 2};
  mbk::DerivativeWeights w, at_50;
  mbk::derivative_weights(e, t, s, 50, at_50);
  for (int i = 2; i < 198; ++i) {
    mbk::derivative_weights(e, t, s, i, w);
    ASSERT_EQ(w.count, 5);
    EXPECT_EQ(w.first, at_50.first) << i;  // the same bits
    EXPECT_EQ(w.second, at_50.second) << i;
    for (int j = 0; j < 5; ++j) {
      EXPECT_NEAR(w.first[j], first[j] / (12 * h), 1e-13 * 8 / (12 * h)) << i << " " << j;
      EXPECT_NEAR(w.second[j], second[j] / (7 * h * h), 1e-13 * 2 / (7 * h * h)) << i << " " << j;
    }
  }
}

// The weights computed once per thread and window (a cache) are those computed afresh, on any
// thread and after any others: a fresh thread's equal this one's after every estimator's windows
// at every sample, for whole-nanosecond stamps and for jittered ones.
TEST(OfflineEstimatorTest, WeightsDoNotDependOnWhatWasComputedBefore) {
  for (const std::vector<double>& t : {bag_stamps(7, 3000), stamps(1000, 3.0, 0.2)}) {
    const mbk::Segments s = mbk::find_segments(t, mbk::default_max_gap(t));
    std::vector<mbk::OfflineEstimator> estimators;
    for (const std::string& name : mbk::offline_estimator_names())
      if (name != "auto") estimators.push_back(mbk::make_offline_estimator(name));
    const int n = static_cast<int>(t.size());
    const std::vector<int> samples = {0, 3, 700, n / 2, n / 2 + 1, n - 2};
    auto all = [&](std::vector<mbk::DerivativeWeights>& out) {
      for (int i : samples)
        for (const mbk::OfflineEstimator& e : estimators) {
          out.emplace_back();
          mbk::derivative_weights(e, t, s, i, out.back());
        }
    };
    mbk::DerivativeWeights scratch;  // every window at every sample first, on this thread
    for (int i = 0; i < n; ++i)
      for (const mbk::OfflineEstimator& e : estimators)
        mbk::derivative_weights(e, t, s, i, scratch);
    std::vector<mbk::DerivativeWeights> here, fresh;
    all(here);
    std::thread([&] { all(fresh); }).join();
    ASSERT_EQ(here.size(), fresh.size());
    for (size_t k = 0; k < here.size(); ++k) {
      EXPECT_EQ(here[k].begin, fresh[k].begin) << k;
      EXPECT_EQ(here[k].value, fresh[k].value) << k;
      EXPECT_EQ(here[k].first, fresh[k].first) << k;
      EXPECT_EQ(here[k].second, fresh[k].second) << k;
    }
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
