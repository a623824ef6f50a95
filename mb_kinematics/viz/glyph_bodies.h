// The bodies of a mb_kinematics_msgs/BodyKinematicsArray as mbk::GlyphBody, for the rviz display
// and the node's markers. A template over the message type, so that viz/ needs no ROS headers:
// it reads name, index, lower_body, pose, mass_center, twist and accel of each body.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk {

template <typename BodyKinematicsArray>
std::vector<GlyphBody> glyph_bodies(const BodyKinematicsArray& msg) {
  auto vec = [](const auto& v) { return Vec3<double>(v.x, v.y, v.z); };
  std::vector<GlyphBody> out(msg.bodies.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const auto& b = msg.bodies[i];
    GlyphBody& g = out[i];
    g.name = b.name;
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
  return out;
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
