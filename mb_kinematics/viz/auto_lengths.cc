#include "mb_kinematics/viz/auto_lengths.h"

#include <algorithm>
#include <cmath>

namespace mbk {

double robot_size(const std::vector<GlyphBody>& bodies) {
  Eigen::AlignedBox3d box;
  for (const GlyphBody& b : bodies) box.extend(b.origin).extend(b.mass_center);
  return box.isEmpty() ? 0 : box.diagonal().norm();
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
  const double longest = fraction * size_;
  for (int q = 0; q < GlyphQuantity::kCount; ++q) {
    const double largest = max_norm(drawn, q);
    double range = ranges_[q].update(time, largest);
    if (!(range > 0)) range = largest;  // a motion that starts after a standstill
    style.scale[q] = range > 0 ? longest / range : 0;
  }
  style.max_length = kAutoCap * longest;
}

}  // namespace mbk
