// The bodies of a mb_kinematics_msgs/BodyKinematicsArray as mbk::GlyphBody, for the rviz display
// and the node's markers. A template over the message type, so that viz/ needs no ROS headers:
// it reads name, index, lower_body, pose, mass_center, twist and accel of each body.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk {

// One body's values, all but its name (left as it is).
template <typename BodyKinematics>
void set_glyph_values(const BodyKinematics& b, GlyphBody& g) {
  auto vec = [](const auto& v) { return Vec3<double>(v.x, v.y, v.z); };
  g.index = b.index;
  g.lower = b.lower_body;
  g.origin = vec(b.pose.position);
  const auto& o = b.pose.orientation;
  g.orientation = Eigen::Quaterniond(o.w, o.x, o.y, o.z);
  g.mass_center = vec(b.mass_center);
  g.vectors[GlyphQuantity::kVelocity] = vec(b.twist.linear);
  g.vectors[GlyphQuantity::kAcceleration] = vec(b.accel.linear);
  g.vectors[GlyphQuantity::kOmega] = vec(b.twist.angular);
  g.vectors[GlyphQuantity::kAlpha] = vec(b.accel.angular);
}

template <typename BodyKinematicsArray>
std::vector<GlyphBody> glyph_bodies(const BodyKinematicsArray& msg) {
  std::vector<GlyphBody> out(msg.bodies.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].name = msg.bodies[i].name;
    set_glyph_values(msg.bodies[i], out[i]);
  }
  return out;
}

// The bodies of `msg` drawn with `style`, each body's mass from `masses` (by name, e.g.
// mbk::urdf_link_masses of robot_description; a body not in it has an unknown mass): one pass
// over the message (two when Min Mass Fraction needs the heaviest body), and only the bodies
// drawn converted to GlyphBody.
template <typename BodyKinematicsArray>
BodySelection select_bodies(const BodyKinematicsArray& msg,
                            const std::map<std::string, double>& masses, const GlyphStyle& style) {
  const size_t n = msg.bodies.size();
  std::vector<double> mass;
  double heaviest = 0;
  if (!masses.empty() && style.min_mass_fraction > 0) {
    mass.assign(n, std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < n; ++i) {
      const auto it = masses.find(msg.bodies[i].name);
      if (it == masses.end()) continue;
      mass[i] = it->second;
      if (std::isfinite(mass[i])) heaviest = std::max(heaviest, mass[i]);
    }
  }
  BodySelection selection(style, heaviest);
  GlyphBody body;
  for (size_t i = 0; i < n; ++i) {
    set_glyph_values(msg.bodies[i], body);
    body.mass = mass.empty() ? std::numeric_limits<double>::quiet_NaN() : mass[i];
    selection.add(msg.bodies[i].name, body);
  }
  return selection;
}

// Each body's mass from `masses` (by name, e.g. mbk::urdf_link_masses of robot_description);
// a body not in it keeps an unknown mass.
inline void set_masses(const std::map<std::string, double>& masses,
                       std::vector<GlyphBody>& bodies) {
  for (GlyphBody& b : bodies) {
    const auto it = masses.find(b.name);
    if (it != masses.end()) b.mass = it->second;
  }
}

}  // namespace mbk
