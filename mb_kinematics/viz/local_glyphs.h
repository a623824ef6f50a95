// The glyphs as a single-precision renderer (Ogre, in the rviz display) takes them. Far from R's
// origin a float cannot tell apart the two ends of a short arrow (at 1e7 m floats are 1 m
// apart), so, as rviz's own displays do with a scene node per frame, the display places its
// scene node at an anchor near the bodies and hands the renderer coordinates relative to it,
// subtracted in double; an arrow goes as its start, unit direction and length, all computed in
// double from the glyph's vector. Every value is finite, whatever the bodies' distance up to
// kMaxGlyphDistance.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk {

// The centre of the box around the mass centers and arrow starts of `glyphs` (0 if none).
Vec3<double> glyph_anchor(const Glyphs& glyphs);

// `p - anchor` in float.
Eigen::Vector3f local_point(const Vec3<double>& p, const Vec3<double>& anchor);

struct LocalArrow {
  Eigen::Vector3f start, direction;  // direction: a unit vector
  float length;
};
// The arrow from `start` along `vector`; nullopt if it has no length a float can hold.
std::optional<LocalArrow> local_arrow(const Vec3<double>& start, const Vec3<double>& vector,
                                      const Vec3<double>& anchor);

}  // namespace mbk
