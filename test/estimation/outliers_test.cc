// Hampel's test for gross outliers (estimation/outliers.h): corrupt samples are found, motion,
// steps, rounding and Gaussian noise are not.
#include "mb_kinematics/estimation/outliers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
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

// Hampel's test as estimation/outliers.h states it, by selection (std::nth_element): the median,
// then the median of the absolute deviations from it.
double reference_median(std::vector<double> v) {
  const int n = static_cast<int>(v.size()), middle = n / 2;
  std::nth_element(v.begin(), v.begin() + middle, v.end());
  const double upper = v[middle];
  if (n % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + middle);
  return lower + (upper - lower) / 2;
}

mbk::OutlierTest reference_test(const std::vector<double>& window, double x) {
  mbk::OutlierTest out;
  out.median = reference_median(window);
  std::vector<double> deviation;
  for (double v : window) deviation.push_back(std::abs(v - out.median));
  out.scale = std::max(1.4826 * reference_median(deviation),
                       mbk::kOutlierFloor * (1 + std::abs(out.median)));
  out.outlier = std::abs(x - out.median) > mbk::kOutlierScales * out.scale;
  return out;
}

// The sorted window's median, scale and verdict are the selection's, bit for bit: windows of 1
// to 80 values (odd and even, past the 64 kept on the stack), with ties, both signs, spikes.
TEST(Outliers, SameBitsAsSelection) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0, 1);
  std::uniform_int_distribution<int> count(1, 80), small(0, 3);
  int outliers = 0;
  for (int k = 0; k < 20000; ++k) {
    std::vector<double> window(k % 4 == 0 ? count(rng) : 7 + k % 5);
    for (double& v : window) {
      v = k % 3 == 0 ? small(rng) * 0.25 : 1.5 + normal(rng) * std::pow(10.0, small(rng) - 3);
      if (normal(rng) > 2.5) v = normal(rng) * 1e30;  // a spike
    }
    const double x = window[k % window.size()];
    const mbk::OutlierTest want = reference_test(window, x);
    std::vector<double> values = window;
    const mbk::OutlierTest got =
        mbk::hampel_test(values.data(), static_cast<int>(values.size()), x);
    ASSERT_EQ(got.median, want.median) << k;
    ASSERT_EQ(got.scale, want.scale) << k;
    ASSERT_EQ(got.outlier, want.outlier) << k;
    outliers += got.outlier;
  }
  EXPECT_GT(outliers, 100);  // the spikes were tested too
}

// Windows already in order or in decreasing order (a smooth series', taken without sorting) give
// the bits of a std::sort'ed window: ties of 0 and -0 keep their order, as std::sort's insertion
// sort keeps them for up to 16 values (longer windows are sorted by std::sort).
TEST(Outliers, WindowsInOrderSameBitsAsSorted) {
  const auto bits = [](double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> count(1, 16), step(0, 2);
  for (int k = 0; k < 20000; ++k) {
    std::vector<double> window(count(rng));
    double v = -0.5 * step(rng);
    for (double& w : window) {  // increasing, with ties and zeros of both signs
      w = v == 0 && step(rng) == 0 ? -0.0 : v;
      v += 0.25 * step(rng);
    }
    if (k % 2 == 1) {  // decreasing: strictly where k % 4 == 1, with ties where k % 4 == 3
      std::reverse(window.begin(), window.end());
      if (k % 4 == 1)
        for (size_t i = 0; i < window.size(); ++i) window[i] = 1.5 * window.size() - i;
    }
    const double x = window[k % window.size()];
    std::vector<double> sorted = window, values = window;
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> in_order = sorted;  // taken as it is
    const mbk::OutlierTest want =
        mbk::hampel_test(in_order.data(), static_cast<int>(in_order.size()), x);
    const mbk::OutlierTest got =
        mbk::hampel_test(values.data(), static_cast<int>(values.size()), x);
    for (size_t i = 0; i < values.size(); ++i) ASSERT_EQ(bits(values[i]), bits(sorted[i])) << k;
    ASSERT_EQ(bits(got.median), bits(want.median)) << k;
    ASSERT_EQ(bits(got.scale), bits(want.scale)) << k;
    ASSERT_EQ(got.outlier, want.outlier) << k;
  }
}

}  // namespace
