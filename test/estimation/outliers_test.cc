// Hampel's test for gross outliers (estimation/outliers.h): corrupt samples are found, motion,
// steps, rounding and Gaussian noise are not.
#include "mb_kinematics/estimation/outliers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

constexpr int kWindow = 2 * mbk::kOutlierHalfWindow + 1;

// Sample `at` of `x` against the window of kWindow samples centred on it.
mbk::OutlierTest test_at(const std::vector<double>& x, int at) {
  std::vector<double> window(x.begin() + at - mbk::kOutlierHalfWindow,
                             x.begin() + at + mbk::kOutlierHalfWindow + 1);
  return mbk::hampel_test(window.data(), kWindow, x[at]);
}

std::vector<double> smooth(int n) {
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = std::sin(0.05 * i);
  return x;
}

TEST(Outliers, AHugeSampleIsOneAndItsNeighboursAreNot) {
  for (double spike : {1e300, -1e300, 1e30, 1e3, 1.7e308}) {
    std::vector<double> x = smooth(40);
    x[20] = spike;
    const mbk::OutlierTest test = test_at(x, 20);
    EXPECT_TRUE(test.outlier) << spike;
    EXPECT_NEAR(test.median, std::sin(0.05 * 20), 0.06) << spike;
    EXPECT_TRUE(std::isfinite(test.scale));
    for (int i = 15; i <= 25; ++i)
      EXPECT_EQ(test_at(x, i).outlier, i == 20) << spike << " at " << i;
  }
}

TEST(Outliers, ASpikeOfHalfTheWindowIsFoundAStepIsNot) {
  std::vector<double> spike = smooth(40), step = smooth(40);
  for (int i = 18; i < 18 + mbk::kOutlierHalfWindow; ++i) spike[i] = 1e30;
  for (int i = 20; i < 40; ++i) step[i] += 1e30;  // a jump that stays
  for (int i = 18; i < 18 + mbk::kOutlierHalfWindow; ++i) EXPECT_TRUE(test_at(spike, i).outlier);
  for (int i = 10; i < 30; ++i) EXPECT_FALSE(test_at(step, i).outlier) << i;
}

TEST(Outliers, MotionRoundingAndNoiseAreNot) {
  // A sharp peak: 0 up to 1.5 rad and back within the window.
  std::vector<double> peak(30, 0.0);
  for (int i = 0; i < 30; ++i) peak[i] = std::max(0.0, 1.5 - 0.3 * std::abs(i - 15));
  for (int i = 5; i < 25; ++i) EXPECT_FALSE(test_at(peak, i).outlier) << i;
  // A still coordinate printed to 6 decimals: one sample a rounding step off, at 0 and at 100.
  for (double level : {0.0, 100.0}) {
    std::vector<double> still(30, level);
    still[15] += 1e-6;
    EXPECT_FALSE(test_at(still, 15).outlier) << level;
  }
  // Gaussian noise: 200,000 windows, none crosses.
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0, 1);
  std::vector<double> x(kWindow);
  int crossed = 0;
  for (int k = 0; k < 200000; ++k) {
    for (double& v : x) v = normal(rng);
    crossed += test_at(x, mbk::kOutlierHalfWindow).outlier;
  }
  EXPECT_EQ(crossed, 0);
}

}  // namespace
