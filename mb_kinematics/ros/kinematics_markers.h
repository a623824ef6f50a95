// The picture of body_kinematics (mb_kinematics/viz/, shared with the rviz display) as a
// visualization_msgs/MarkerArray, for the node's ~publish_markers.
#pragma once

#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <visualization_msgs/MarkerArray.h>

#include <vector>

#include "mb_kinematics/viz/glyph_bodies.h"
#include "mb_kinematics/viz/glyphs.h"

namespace mbk_ros {

// The picture's vocabulary, in the namespace of its ROS users.
using mbk::GlyphArc;
using mbk::GlyphArrow;
using mbk::GlyphQuantity;
using mbk::Glyphs;
using mbk::GlyphStyle;
using mbk::kDefaultBodyFilter;
using mbk::Rgba;

// mbk::max_norm and mbk::make_glyphs on the message's bodies; everything in its frame (R).
double max_norm(const mb_kinematics_msgs::BodyKinematicsArray& msg, const GlyphStyle& style, int q);
Glyphs make_glyphs(const mb_kinematics_msgs::BodyKinematicsArray& msg, const GlyphStyle& style);

// The picture as markers in msg.header.frame_id: a DELETEALL first, then arrows (ns per
// quantity; pose at the arrow's start, points 0 and the arrow's vector), arcs (LINE_STRIP + ARROW
// heads, ns "<quantity>_arc"), SPHERE_LIST "mass_centers", LINE_LIST "skeleton".
visualization_msgs::MarkerArray make_marker_array(const Glyphs& glyphs, const GlyphStyle& style,
                                                  const std_msgs::Header& header);

}  // namespace mbk_ros
