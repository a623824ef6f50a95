// Gross outliers in a recorded series (a 1e300 among angles: a corrupt sample, not motion),
// found by Hampel's identifier before anything is estimated from the series: sample x_i is an
// outlier when it lies farther from the median m of the window of 2 kOutlierHalfWindow + 1
// samples around it (x_i included; shifted at the ends) than kOutlierScales robust scales,
//   |x_i - m| > kOutlierScales max(1.4826 MAD, kOutlierFloor (1 + |m|)),
// MAD the window's median absolute deviation from m (1.4826 MAD estimates a Gaussian's sigma; the
// floor keeps a window of equal values from making every rounding step an outlier). The median
// and MAD ignore up to half the window: a spike of up to kOutlierHalfWindow samples is found, a
// step (a jump that stays) is not. Gaussian noise crosses the threshold with a probability far
// below 1e-12 per sample. ROS-free.
#pragma once

namespace mbk {

constexpr int kOutlierHalfWindow = 5;
constexpr double kOutlierScales = 1000, kOutlierFloor = 1e-6;
// The fewest samples a window must hold to judge one of them (a sparse series: fewer, no test).
constexpr int kOutlierMinimumWindow = 7;

struct OutlierTest {
  bool outlier = false;
  double median = 0, scale = 0;  // m and max(1.4826 MAD, the floor)
};

// Is x an outlier of the window `values` (count of them, x among them)? values is reordered.
OutlierTest hampel_test(double* values, int count, double x);

}  // namespace mbk
