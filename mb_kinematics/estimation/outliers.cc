#include "mb_kinematics/estimation/outliers.h"

#include <algorithm>
#include <cmath>

namespace mbk {
namespace {

// The median of values[0, count), reordering them.
double median_of(double* values, int count) {
  const int middle = count / 2;
  std::nth_element(values, values + middle, values + count);
  const double upper = values[middle];
  if (count % 2 == 1) return upper;
  const double lower = *std::max_element(values, values + middle);
  return lower + (upper - lower) / 2;  // no overflow for values near the double's limit
}

}  // namespace

OutlierTest hampel_test(double* values, int count, double x) {
  OutlierTest out;
  out.median = median_of(values, count);
  for (int i = 0; i < count; ++i) values[i] = std::abs(values[i] - out.median);
  const double mad = median_of(values, count);
  out.scale = std::max(1.4826 * mad, kOutlierFloor * (1 + std::abs(out.median)));
  out.outlier = std::abs(x - out.median) > kOutlierScales * out.scale;
  return out;
}

}  // namespace mbk
