#include "mb_kinematics/viz/auto_lengths.h"

#include <algorithm>
#include <cmath>

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
  if (!values_.empty() && time < values_.back().first) values_.clear();
  values_.emplace_back(time, value);
  while (values_.size() > kMaxValues || values_.front().first < time - window_) values_.pop_front();
  scratch_.clear();
  for (const auto& v : values_) scratch_.push_back(v.second);
  // The smallest value with at least `quantile` of them at or below it.
  const size_t n = scratch_.size();
  const size_t at =
      std::min(n - 1, static_cast<size_t>(std::max(0.0, std::ceil(quantile_ * n) - 1)));
  std::nth_element(scratch_.begin(), scratch_.begin() + at, scratch_.end());
  return scratch_[at];
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
