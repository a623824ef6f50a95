// The median of a stream of values in memory bounded independently of the stream's length: a
// histogram over the values' binary exponent and their top kMantissaBits mantissa bits (bins of
// relative width 2^-kMantissaBits, 1024 per octave, allocated for the octaves that occur), each
// bin keeping its count, least and greatest value and how often the least occurs. The median
// (the value of rank n / 2 in increasing order, as nth_element's) is the bin's least value where
// that rank falls on it (a repeated floor: exact), else the middle of the bin's least and greatest
// values: within 2^-(kMantissaBits + 1) of the exact median, relative (about 5e-4). Values of any
// sign; NaN sorts last. Beside ExactMedian (exact, but a pass over the same values each time it
// narrows) for values made once, as the rows are computed (mbk bag's error bars): ExactMedian
// would need them computed again per pass. Not for the median interval between stamps, which
// must be exact (ExactMedianTest.JitteredStampsGiveTheWholeRecordingsMaxGapWhereAHistogramDoesNot).
// The first kExactValues values are kept as they are (8 bytes each, the median exact), the bins
// made only after: a short recording of a large model (mbk bag keeps two of these per
// coordinate) takes memory in proportion to its values, not 32 KiB per column. ROS-free.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

namespace mbk {

class MedianHistogram {
 public:
  static constexpr int kMantissaBits = 10;
  static constexpr int kExactValues = 1024;  // kept as values (8 KiB) before the bins are made

  void add(double value);
  // The value of rank count() / 2, to the precision above; 0 when empty.
  double median() const;
  std::uint64_t count() const { return count_; }
  // The bytes its values or bins take: 8 per value up to kExactValues, then at most 32 KiB per
  // octave that occurs, whatever the count.
  std::size_t bytes() const;

 private:
  void add_to_bins(double value);

  struct Bin {
    std::uint64_t count = 0, least_count = 0;
    double least = 0, greatest = 0;
  };
  std::vector<double> values_;                         // the first values, before any bin
  std::map<std::uint32_t, std::vector<Bin>> octaves_;  // by sign and exponent, increasing
  std::uint64_t count_ = 0;
};

}  // namespace mbk
