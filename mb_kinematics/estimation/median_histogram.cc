#include "mb_kinematics/estimation/median_histogram.h"

#include <algorithm>
#include <cstring>

namespace mbk {

namespace {

constexpr int kShift = 52 - MedianHistogram::kMantissaBits;
constexpr std::uint64_t kSignBit = std::uint64_t{1} << 63;

// The value's bits as an unsigned integer in the values' order (negatives reversed below the
// positives).
std::uint64_t ordered_bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits & kSignBit ? ~bits : bits | kSignBit;
}

}  // namespace

void MedianHistogram::add(double value) {
  if (count_ < kExactValues) {
    values_.push_back(value);
    ++count_;
    return;
  }
  if (!values_.empty()) {  // the bins take over
    count_ = 0;
    for (double v : values_) add_to_bins(v);
    std::vector<double>().swap(values_);
  }
  add_to_bins(value);
}

void MedianHistogram::add_to_bins(double value) {
  const std::uint64_t key = ordered_bits(value);
  std::vector<Bin>& octave = octaves_[static_cast<std::uint32_t>(key >> 52)];
  if (octave.empty()) octave.resize(std::size_t{1} << kMantissaBits);
  Bin& bin = octave[(key >> kShift) & ((std::uint64_t{1} << kMantissaBits) - 1)];
  ++count_;
  if (bin.count++ == 0 || value < bin.least) {
    bin.least = value, bin.least_count = 1;
    if (bin.count == 1) bin.greatest = value;
  } else if (value == bin.least) {
    ++bin.least_count;
  }
  if (value > bin.greatest) bin.greatest = value;
}

double MedianHistogram::median() const {
  std::uint64_t rank = count_ / 2;
  if (!values_.empty()) {  // in the bins' order: NaN last
    std::vector<double> v = values_;
    std::nth_element(v.begin(), v.begin() + rank, v.end(),
                     [](double a, double b) { return ordered_bits(a) < ordered_bits(b); });
    return v[rank];
  }
  for (const auto& entry : octaves_)
    for (const Bin& bin : entry.second) {
      if (rank >= bin.count) {
        rank -= bin.count;
        continue;
      }
      if (rank < bin.least_count) return bin.least;
      return bin.least + (bin.greatest - bin.least) / 2;
    }
  return 0;  // empty
}

std::size_t MedianHistogram::bytes() const {
  return values_.capacity() * sizeof(double) + octaves_.size() * (sizeof(Bin) << kMantissaBits);
}

}  // namespace mbk
