#include "mb_kinematics/viz/local_glyphs.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace mbk {

Vec3<double> glyph_anchor(const Glyphs& glyphs) {
  Eigen::AlignedBox3d box;
  for (const Vec3<double>& g : glyphs.mass_centers) box.extend(g);
  for (const GlyphArrow& a : glyphs.arrows) box.extend(a.start);
  for (const auto& line : glyphs.skeleton) box.extend(line.first).extend(line.second);
  if (box.isEmpty()) return Vec3<double>::Zero();
  return box.center();
}

Eigen::Vector3f local_point(const Vec3<double>& p, const Vec3<double>& anchor) {
  return (p - anchor).cast<float>();
}

std::optional<LocalArrow> local_arrow(const Vec3<double>& start, const Vec3<double>& vector,
                                      const Vec3<double>& anchor) {
  const double length = vector.norm();
  if (!(length >= std::numeric_limits<float>::min() && length <= std::numeric_limits<float>::max()))
    return std::nullopt;
  const Eigen::Vector3f s = local_point(start, anchor);
  if (!s.allFinite()) return std::nullopt;
  return LocalArrow{s, (vector / length).cast<float>(), static_cast<float>(length)};
}

}  // namespace mbk
