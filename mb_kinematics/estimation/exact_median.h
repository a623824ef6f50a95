// The exact median of values that can be read again (a recording's intervals between stamps), in
// memory bounded independently of their count: each pass over the same values counts them in at
// most max_entries bins of the range still open. A pass whose bins are single values gives the
// median exactly; otherwise the range narrows to the median's bin and another pass is needed.
// Bins start as single values and double in width (merged) whenever there are more than
// max_entries of them: a few distinct values (a steady rate) take one pass; n distinct values in
// general about log(n) / log(max_entries) + 1. The median is the value of rank n / 2 in increasing
// order, as std::nth_element's (offline_estimator.h's default_max_gap). Finite values; -0 is 0.
// Beside MedianHistogram (one pass, to 2^-11) because mbk bag's streamed path needs the median
// interval exactly: its default --max-gap must be the whole-recording path's bit for bit, or
// the two paths split a recording into other segments (ExactMedianTest.
// JitteredStampsGiveTheWholeRecordingsMaxGapWhereAHistogramDoesNot; for mbk bag itself,
// BagTest.JitteredStampsGiveTheWholeRecordingsMaxGap). ROS-free.
#pragma once

#include <cstdint>
#include <map>

namespace mbk {

class ExactMedian {
 public:
  explicit ExactMedian(std::size_t max_entries = 1 << 14) : max_entries_(max_entries) {}

  void add(double value);  // in this pass
  // Ends a pass: true when median() is exact; false when the same values are needed once more
  // (add each again, then finish_pass()). Throws std::runtime_error if a pass saw another count.
  bool finish_pass();
  double median() const { return median_; }  // after finish_pass() returned true; 0 when empty
  int passes() const { return passes_; }
  // The most bytes the bins took in any pass (about 48 per bin; at most max_entries + 1 bins).
  std::size_t peak_bytes() const;

 private:
  void merge_bins();  // bins of twice the width

  std::size_t max_entries_;
  std::uint64_t lo_ = 0, hi_ = ~std::uint64_t{0};  // the range of keys still open (inclusive)
  int shift_ = 0;                                  // bins of 2^shift_ keys from lo_
  std::map<std::uint64_t, std::uint64_t> bins_;    // (key - lo_) >> shift_ -> count
  std::uint64_t count_ = 0, below_ = 0;            // this pass: all values, those below lo_
  std::uint64_t first_count_ = 0;                  // the first pass's count
  std::size_t peak_bins_ = 0;
  int passes_ = 0;
  double median_ = 0;
};

}  // namespace mbk
