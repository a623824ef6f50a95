#include "mb_kinematics/estimation/median_histogram.h"

#include <cstring>

namespace mbk {

namespace {

constexpr int kShift = 52 - MedianHistogram::kMantissaBits;
constexpr std::uint64_t kSign = std::uint64_t{1} << 63;

// The value's bits as an unsigned integer in the values' order (negatives reversed below the
// positives).
std::uint64_t ordered_bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits & kSign ? ~bits : bits | kSign;
}

}  // namespace

void MedianHistogram::add(double value) {
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
  return octaves_.size() * (sizeof(Bin) << kMantissaBits);
}

}  // namespace mbk
