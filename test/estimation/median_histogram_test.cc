// MedianHistogram (estimation/median_histogram.h): its median is the exact one (computed here by
// nth_element) to the stated relative 2^-11, exact on a repeated floor value, and its memory does
// not grow with the number of values.
#include "mb_kinematics/estimation/median_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

constexpr double kPrecision = 1.0 / (2 << mbk::MedianHistogram::kMantissaBits);  // 2^-11

double exact_median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double histogram_median(const std::vector<double>& v) {
  mbk::MedianHistogram h;
  for (double x : v) h.add(x);
  EXPECT_EQ(h.count(), v.size());
  return h.median();
}

// Log-normal values over several octaves, of either sign, n odd and even.
TEST(MedianHistogramTest, EqualsTheExactMedianToTheStatedPrecision) {
  std::mt19937 rng(7);
  std::lognormal_distribution<double> spread(-11.0, 1.5);
  for (int n : {1, 2, 3, 10, 101, 1000, 20001}) {
    for (double sign : {1.0, -1.0}) {
      std::vector<double> v;
      for (int i = 0; i < n; ++i) v.push_back(sign * spread(rng));
      const double exact = exact_median(v);
      EXPECT_NEAR(histogram_median(v), exact, kPrecision * std::abs(exact)) << n << " " << sign;
    }
  }
  std::vector<double> mixed = {-3.0, -1e-300, 0.0, 2.5, 1e300, -0.0, 7.0};
  EXPECT_EQ(histogram_median(mixed), exact_median(mixed));
}

// The precision is used, not only met: values packed within one bin differ from the exact
// median by less than 2^-11 but not always by 0.
TEST(MedianHistogramTest, WithinOneBinTheMiddleOfItsValues) {
  std::vector<double> v;
  for (int i = 0; i < 99; ++i) v.push_back(1.0 + i * 1e-6);
  const double median = histogram_median(v);
  EXPECT_NEAR(median, exact_median(v), kPrecision);
  EXPECT_EQ(median, 1.0 + (98e-6) / 2);
}

// The standard errors of "auto" at uniform stamps: most samples at one floor value, a tail above;
// the median on the floor is exact.
TEST(MedianHistogramTest, ExactOnARepeatedFloor) {
  std::mt19937 rng(3);
  std::exponential_distribution<double> tail(1.0);
  const double floor = 1.3200617e-6;
  std::vector<double> v;
  for (int i = 0; i < 10001; ++i) v.push_back(i % 3 == 0 ? floor * (1 + tail(rng)) : floor);
  EXPECT_EQ(histogram_median(v), exact_median(v));
  EXPECT_EQ(histogram_median(v), floor);
}

// 1e4 and 1e5 values spread over the same octaves: the same bytes, a bounded few per octave.
TEST(MedianHistogramTest, MemoryDoesNotGrowWithTheCount) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jittered(0.8e-3, 1.2e-3);
  mbk::MedianHistogram small, large;
  for (int i = 0; i < 10000; ++i) small.add(jittered(rng));
  for (int i = 0; i < 100000; ++i) large.add(jittered(rng));
  EXPECT_EQ(small.bytes(), large.bytes());
  EXPECT_LE(large.bytes(), 2u * 32768);  // 0.8e-3 .. 1.2e-3: two octaves
}

// Fewer values than kExactValues take 8 bytes each (the vector's growth aside) and give the
// exact median; the next value moves them into bins.
TEST(MedianHistogramTest, FewValuesTakeTheirOwnSize) {
  mbk::MedianHistogram h;
  std::vector<double> v;
  for (int i = 0; i < 3; ++i) h.add(1.0 + i), v.push_back(1.0 + i);
  EXPECT_LE(h.bytes(), 4 * sizeof(double));
  EXPECT_EQ(h.median(), 2.0);
  for (int i = 3; i < mbk::MedianHistogram::kExactValues; ++i)
    h.add(std::sqrt(1.0 + i)), v.push_back(std::sqrt(1.0 + i));
  EXPECT_LE(h.bytes(), mbk::MedianHistogram::kExactValues * sizeof(double));
  EXPECT_EQ(h.median(), exact_median(v));
  h.add(5.0), v.push_back(5.0);
  EXPECT_EQ(h.count(), v.size());
  EXPECT_NEAR(h.median(), exact_median(v), kPrecision * exact_median(v));
  EXPECT_GE(h.bytes(), 32768u);  // bins now
}

}  // namespace
