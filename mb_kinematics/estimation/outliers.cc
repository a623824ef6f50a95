#include "mb_kinematics/estimation/outliers.h"

#include <algorithm>
#include <cmath>

namespace mbk {
namespace {

// The median of values[0, count) in increasing order.
double median_of_sorted(const double* values, int count) {
  const int middle = count / 2;
  const double upper = values[middle];
  if (count % 2 == 1) return upper;
  const double lower = values[middle - 1];
  return lower + (upper - lower) / 2;  // no overflow for values near the double's limit
}

// The windows kept on the stack (a recording's are 2 kOutlierHalfWindow + 1 long).
constexpr int kMostOnStack = 64;

// values[0, count) in increasing order, as std::sort orders them; a window already in order, or
// in strictly decreasing order (a smooth series' windows, but near its turns), without sorting.
// Up to 16 values std::sort is an insertion sort, which keeps equal values (0 and -0) in their
// order, as a window in order keeps them; a strictly decreasing one has no equal values.
void sort_window(double* values, int count) {
  bool increasing = count <= 16, decreasing = count <= 16;
  for (int i = 1; i < count && (increasing || decreasing); ++i) {
    increasing = increasing && !(values[i] < values[i - 1]);
    decreasing = decreasing && values[i] < values[i - 1];
  }
  if (decreasing)
    std::reverse(values, values + count);
  else if (!increasing)
    std::sort(values, values + count);
}

}  // namespace

// The window sorted once; its deviations |v - m| then come in increasing order by merging the two
// sides of the median (each side's deviations are monotone in v, rounding included), and their
// median is the same value any selection finds.
OutlierTest hampel_test(double* values, int count, double x) {
  OutlierTest out;
  double deviations[kMostOnStack];
  double* const d = count <= kMostOnStack ? deviations : values;
  sort_window(values, count);
  out.median = median_of_sorted(values, count);
  const double m = out.median;
  if (d == values) {  // a long window: in place, sorted again
    for (int i = 0; i < count; ++i) values[i] = std::abs(values[i] - m);
    std::sort(values, values + count);
  } else {
    int right = static_cast<int>(std::lower_bound(values, values + count, m) - values),
        left = right - 1;
    for (int k = 0; k <= count / 2; ++k) {  // the deviations' smallest count / 2 + 1
      const double below = left >= 0 ? std::abs(values[left] - m) : HUGE_VAL,
                   above = right < count ? std::abs(values[right] - m) : HUGE_VAL;
      if (right >= count || (left >= 0 && below <= above))
        d[k] = below, --left;
      else
        d[k] = above, ++right;
    }
  }
  const double mad = median_of_sorted(d, count);
  out.scale = std::max(1.4826 * mad, kOutlierFloor * (1 + std::abs(out.median)));
  out.outlier = std::abs(x - out.median) > kOutlierScales * out.scale;
  return out;
}

}  // namespace mbk
