#include "mb_kinematics/io/bvh_bones.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mbk {
namespace {

constexpr double kRelativeChange = 1e-3;
constexpr double kAbsoluteChange = 1e-6;  // metres

bool has_positions(const BvhSegment& s) {
  return std::any_of(s.channels.begin(), s.channels.end(),
                     [](BvhChannel c) { return !is_rotation(c); });
}

// The bone's length in frame f: the OFFSET with the position channels' axes replaced.
double length_in(const BvhFile& bvh, const BvhSegment& s, int f, double scale) {
  Eigen::Vector3d t = s.offset;
  for (size_t i = 0; i < s.channels.size(); ++i)
    if (!is_rotation(s.channels[i]))
      t[static_cast<int>(s.channels[i]) % 3] = bvh.value(f, s.first_column + static_cast<int>(i));
  return scale * t.norm();
}

bool constant_channels(const BvhFile& bvh, const BvhSegment& s) {
  for (size_t i = 0; i < s.channels.size(); ++i) {
    const int column = s.first_column + static_cast<int>(i);
    for (int f = 1; f < bvh.frame_count; ++f)
      if (bvh.value(f, column) != bvh.value(0, column)) return false;
  }
  return true;
}

}  // namespace

std::vector<bool> fixed_in_space(const BvhFile& bvh) {
  std::vector<bool> fixed(bvh.segments.size());
  for (size_t i = 0; i < bvh.segments.size(); ++i) {
    const BvhSegment& s = bvh.segments[i];
    fixed[i] = (s.parent < 0 || fixed[s.parent]) && constant_channels(bvh, s);
  }
  return fixed;
}

std::vector<BoneLength> changing_bones(const BvhFile& bvh, double scale) {
  std::vector<BoneLength> bones;
  const std::vector<bool> fixed = fixed_in_space(bvh);
  for (const BvhSegment& s : bvh.segments) {
    if (s.parent < 0 || fixed[s.parent] || !has_positions(s) || bvh.frame_count == 0) continue;
    BoneLength b{s.name, INFINITY, 0};
    for (int f = 0; f < bvh.frame_count; ++f) {
      const double length = length_in(bvh, s, f, scale);
      b.min = std::min(b.min, length);
      b.max = std::max(b.max, length);
    }
    if (b.max - b.min > kRelativeChange * b.max + kAbsoluteChange) bones.push_back(b);
  }
  return bones;
}

std::string changing_bones_warning(const BvhFile& bvh, double scale) {
  const std::vector<BoneLength> bones = changing_bones(bvh, scale);
  if (bones.empty()) return "";
  std::string out = bvh.path +
                    ": bone lengths change during the motion (position channels of a JOINT "
                    "are its whole translation; a human's bones keep their length):";
  for (const BoneLength& b : bones) {
    char text[64];
    std::snprintf(text, sizeof text, " %.4g-%.4g m,", b.min, b.max);
    out += " " + b.name + text;
  }
  out.pop_back();
  return out;
}

}  // namespace mbk
