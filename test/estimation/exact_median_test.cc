// ExactMedian (estimation/exact_median.h): over as many passes as it asks for, its median is
// nth_element's, bit for bit, for values of every sign and magnitude, and its bins stay within
// the stated bound whatever the number of values; on jittered stamps the one-pass MedianHistogram
// is not (why mbk bag's streamed path keeps both).
#include "mb_kinematics/estimation/exact_median.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "mb_kinematics/estimation/median_histogram.h"
#include "mb_kinematics/estimation/offline_estimator.h"

namespace {

double nth_element_median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The median of v through as many passes as ExactMedian asks for; their number in `passes`.
double passes_median(const std::vector<double>& v, std::size_t max_entries, int* passes = nullptr,
                     std::size_t* peak_bytes = nullptr) {
  mbk::ExactMedian m(max_entries);
  do {
    for (double x : v) m.add(x);
  } while (!m.finish_pass() && m.passes() < 100);
  if (passes) *passes = m.passes();
  if (peak_bytes) *peak_bytes = m.peak_bytes();
  return m.median();
}

// Intervals of a steady 1 kHz clock: a few distinct values, one pass.
TEST(ExactMedianTest, AFewDistinctValuesTakeOnePass) {
  std::vector<double> v;
  for (int i = 1; i < 10000; ++i) v.push_back((1.0 + i * 1e-3) - (1.0 + (i - 1) * 1e-3));
  int passes = 0;
  EXPECT_EQ(passes_median(v, 1 << 14, &passes), nth_element_median(v));
  EXPECT_EQ(passes, 1);
}

// Values of every sign and of magnitudes from 1e-300 to 1e300, zeros of both signs among them,
// n odd and even, bins from 2 (many passes) to more than the values (one pass).
TEST(ExactMedianTest, EqualsNthElementBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> exponent(-300, 300), unit(-1, 1);
  for (int n : {1, 2, 3, 10, 101, 1000, 4001}) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i) {
      const double x = unit(rng);
      v.push_back(i % 17 == 0 ? 0.0 * x : x * std::pow(10.0, i % 3 ? exponent(rng) : 0));
    }
    const double exact = nth_element_median(v);
    for (std::size_t bins : {2, 3, 64, 5000}) {
      int passes = 0;
      const double m = passes_median(v, bins, &passes);
      EXPECT_EQ(m, exact) << n << " values, " << bins << " bins, " << passes << " passes";
      EXPECT_FALSE(std::signbit(m) && m == 0);  // -0 as 0
      if (static_cast<std::size_t>(n) > bins) {
        EXPECT_GT(passes, 1);
      }
    }
  }
  EXPECT_EQ(passes_median({}, 4), 0.0);
}

// Jittered 1 kHz stamps, every interval distinct: two passes, the bins bounded by the limit
// whether there are 10^4 or 10^6 values, and the median exact.
TEST(ExactMedianTest, DistinctValuesTakeBoundedMemory) {
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0, 5e-5);
  std::size_t short_bytes = 0, long_bytes = 0;
  for (int n : {10000, 1000000}) {
    std::vector<double> v;
    double last = 0;
    for (int i = 1; i <= n; ++i) {
      const double t = i * 1e-3 + jitter(rng);
      v.push_back(t - last), last = t;
    }
    int passes = 0;
    std::size_t& bytes = n == 10000 ? short_bytes : long_bytes;
    EXPECT_EQ(passes_median(v, 1 << 12, &passes, &bytes), nth_element_median(v)) << n;
    EXPECT_EQ(passes, 2) << n;
  }
  const std::size_t bound = ((1 << 12) + 1) * 48;
  EXPECT_LE(short_bytes, bound);
  EXPECT_LE(long_bytes, bound);
  EXPECT_GT(long_bytes, bound / 4);  // the bins were used, not skipped
}

// A second pass over other values than the first is an error, not a wrong median.
TEST(ExactMedianTest, ValuesThatChangeBetweenPassesAreAnError) {
  mbk::ExactMedian m(2);
  for (double x : {1.0, 2.0, 3.0, 4.0, 5.0}) m.add(x);
  ASSERT_FALSE(m.finish_pass());
  for (double x : {1.0, 2.0, 3.0, 4.0}) m.add(x);
  EXPECT_THROW(m.finish_pass(), std::runtime_error);
  mbk::ExactMedian shifted(2);
  for (double x : {1.0, 2.0, 3.0, 4.0, 5.0}) shifted.add(x);
  ASSERT_FALSE(shifted.finish_pass());
  for (double x : {10.0, 20.0, 30.0, 40.0, 50.0}) shifted.add(x);
  EXPECT_THROW(shifted.finish_pass(), std::runtime_error);
}

// Jittered stamps, as mbk bag reads them (BagTest.JitteredStampsGiveTheWholeRecordingsMaxGap):
// 5 x ExactMedian's median of their intervals is default_max_gap (the whole-recording path's)
// bit for bit; MedianHistogram's, within its 2^-11, is another max gap: the streamed and the
// whole-recording paths would split the recording into other segments.
TEST(ExactMedianTest, JitteredStampsGiveTheWholeRecordingsMaxGapWhereAHistogramDoesNot) {
  std::vector<double> t, intervals;
  for (int i = 0; i < 20000; ++i) t.push_back(1 + 1e-3 * i + 3e-4 * std::sin(0.7 * i));
  for (std::size_t i = 1; i < t.size(); ++i) intervals.push_back(t[i] - t[i - 1]);
  int passes = 0;
  EXPECT_EQ(5 * passes_median(intervals, 1 << 14, &passes), mbk::default_max_gap(t));
  EXPECT_GT(passes, 1);
  mbk::MedianHistogram histogram;
  for (double x : intervals) histogram.add(x);
  EXPECT_NE(5 * histogram.median(), mbk::default_max_gap(t));
  EXPECT_NEAR(histogram.median(), nth_element_median(intervals), 1e-3 / 2048);
}

}  // namespace
