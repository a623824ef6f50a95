#include "mb_kinematics/estimation/exact_median.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace mbk {

namespace {

constexpr std::uint64_t kSign = std::uint64_t{1} << 63;

// A key of the same order as the finite doubles: the bits, negatives' flipped.
std::uint64_t key_of(double x) {
  x += 0.0;  // -0 as 0
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return (bits & kSign) ? ~bits : bits | kSign;
}

double value_of(std::uint64_t key) {
  const std::uint64_t bits = (key & kSign) ? key & ~kSign : ~key;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

}  // namespace

void ExactMedian::add(double value) {
  ++count_;
  const std::uint64_t k = key_of(value);
  if (k < lo_) {
    ++below_;
  } else if (k <= hi_) {
    ++bins_[(k - lo_) >> shift_];
    peak_bins_ = std::max(peak_bins_, bins_.size());
    while (bins_.size() > std::max<std::size_t>(max_entries_, 2)) merge_bins();
  }
}

void ExactMedian::merge_bins() {
  std::map<std::uint64_t, std::uint64_t> wider;
  for (const auto& [bin, count] : bins_) wider[bin >> 1] += count;
  bins_.swap(wider);
  ++shift_;  // at most 63: two bins of 2^63 keys are within max_entries
}

bool ExactMedian::finish_pass() {
  if (++passes_ == 1) first_count_ = count_;
  if (count_ == 0 && first_count_ == 0) return true;
  std::uint64_t rank = first_count_ / 2, bin = 0;
  bool found = count_ == first_count_ && below_ <= rank;
  if (found) {
    rank -= below_;  // within the open range
    found = false;
    for (const auto& [b, count] : bins_) {
      if (rank < count) {
        bin = b, found = true;
        break;
      }
      rank -= count;
    }
  }
  if (!found)
    throw std::runtime_error("the values changed between passes (" + std::to_string(count_) +
                             " read, " + std::to_string(first_count_) + " before)");
  const std::uint64_t lo = lo_ + (bin << shift_);
  const bool exact = shift_ == 0;
  if (exact) median_ = value_of(lo);
  hi_ = std::min(hi_, lo + ((std::uint64_t{1} << shift_) - 1));
  lo_ = lo;
  bins_.clear();
  shift_ = 0;
  count_ = below_ = 0;
  return exact;
}

std::size_t ExactMedian::peak_bytes() const {
  return peak_bins_ * (2 * sizeof(std::uint64_t) + 32);  // a std::map node: key, count, links
}

}  // namespace mbk
