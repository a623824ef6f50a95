#include "mb_kinematics/viz/auto_lengths.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace mbk {

double robot_size(const std::vector<GlyphBody>& bodies) {
  Eigen::AlignedBox3d box;
  for (const GlyphBody& b : bodies) box.extend(b.origin).extend(b.mass_center);
  return box.isEmpty() ? 0 : box.diagonal().norm();
}

double auto_longest(double fraction, double size, const GlyphStyle& style) {
  return std::max(fraction * size,
                  kMinLongestRadii * std::max(style.sphere_radius, style.arc_radius));
}

double RunningQuantile::update(double time, double value) {
  if (std::isnan(value)) value = std::numeric_limits<double>::infinity();
  if (!values_.empty() && time < values_.back().first) {
    values_.clear();
    low_.clear();
    high_.clear();
  }
  values_.emplace_back(time, value);
  (low_.empty() || value <= *low_.rbegin() ? low_ : high_).insert(value);
  while (values_.size() > kMaxValues || values_.front().first < time - window_) {
    erase(values_.front().second);
    values_.pop_front();
  }
  balance();
  return *low_.rbegin();
}

// Removes one copy of `value` from the half that holds it.
void RunningQuantile::erase(double value) {
  std::multiset<double>& half = !low_.empty() && value <= *low_.rbegin() ? low_ : high_;
  half.erase(half.find(value));
}

// Moves values between the halves until low_ holds the `at` + 1 smallest, where `at` is the
// quantile's index in the sorted window.
void RunningQuantile::balance() {
  const size_t n = values_.size();
  const size_t at =
      std::min(n - 1, static_cast<size_t>(std::max(0.0, std::ceil(quantile_ * n) - 1)));
  while (low_.size() > at + 1) {
    high_.insert(high_.begin(), *low_.rbegin());
    low_.erase(std::prev(low_.end()));
  }
  while (low_.size() < at + 1) {
    low_.insert(low_.end(), *high_.begin());
    high_.erase(high_.begin());
  }
}

AutoLengths::AutoLengths()
    : sizes_(kAutoWindow, 1.0),
      ranges_{{{kAutoWindow, kAutoQuantile},
               {kAutoWindow, kAutoQuantile},
               {kAutoWindow, kAutoQuantile},
               {kAutoWindow, kAutoQuantile}}} {}

void AutoLengths::update(double time, const BodySelection& drawn, double fraction,
                         GlyphStyle& style) {
  const double size = robot_size(drawn.drawn());
  if (size > 0) size_ = sizes_.update(time, size);
  const double longest = auto_longest(fraction, size_, style);
  for (int q = 0; q < GlyphQuantity::kCount; ++q) {
    const double largest = max_norm(drawn, q);
    double range = ranges_[q].update(time, largest);
    if (!(range > 0)) range = largest;  // a motion that starts after a standstill
    const double scale = longest / range;
    if (std::isfinite(scale) && scale > 0) style.scale[q] = scale;
  }
  style.max_length = kAutoCap * longest;
}

}  // namespace mbk
