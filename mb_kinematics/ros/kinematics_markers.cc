#include "mb_kinematics/ros/kinematics_markers.h"

#include <algorithm>

namespace mbk_ros {
namespace {

using mbk::Vec3;

visualization_msgs::Marker marker(const std_msgs::Header& header, const std::string& ns, int id,
                                  int type, const Rgba& c) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1;
  m.color.r = c.r;
  m.color.g = c.g;
  m.color.b = c.b;
  m.color.a = c.a;
  return m;
}

geometry_msgs::Point point(const Vec3<double>& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

// Placed at `from` (the marker's pose), its points 0 and `vector`: rviz turns points into floats,
// which far from R's origin cannot tell the two ends of a short arrow apart.
visualization_msgs::Marker arrow_marker(const std_msgs::Header& header, const std::string& ns,
                                        int id, const Rgba& c, const Vec3<double>& from,
                                        const Vec3<double>& vector, double width) {
  visualization_msgs::Marker m = marker(header, ns, id, visualization_msgs::Marker::ARROW, c);
  m.pose.position = point(from);
  m.points = {point(Vec3<double>::Zero()), point(vector)};
  m.scale.x = width;
  m.scale.y = 2 * width;
  m.scale.z = std::min(3 * width, 0.5 * vector.norm());
  return m;
}

}  // namespace

double max_norm(const mb_kinematics_msgs::BodyKinematicsArray& msg, const GlyphStyle& style,
                int q) {
  return mbk::max_norm(mbk::select_bodies(msg, {}, style), q);
}

Glyphs make_glyphs(const mb_kinematics_msgs::BodyKinematicsArray& msg, const GlyphStyle& style) {
  return mbk::make_glyphs(mbk::select_bodies(msg, {}, style), style);
}

visualization_msgs::MarkerArray make_marker_array(const Glyphs& glyphs, const GlyphStyle& style,
                                                  const std_msgs::Header& header) {
  using visualization_msgs::Marker;
  visualization_msgs::MarkerArray out;
  Marker clear;
  clear.header = header;
  clear.action = Marker::DELETEALL;
  out.markers.push_back(clear);
  int id = 0;
  for (const GlyphArrow& a : glyphs.arrows)
    out.markers.push_back(arrow_marker(header, mbk::glyph_quantity_name(a.quantity), id++,
                                       style.color[a.quantity], a.start, a.vector, style.width));
  for (const GlyphArc& arc : glyphs.arcs) {
    const std::string ns = std::string(mbk::glyph_quantity_name(arc.quantity)) + "_arc";
    const Rgba& c = style.color[arc.quantity];
    Marker line = marker(header, ns, id++, Marker::LINE_STRIP, c);
    for (const Vec3<double>& p : arc.points) line.points.push_back(point(p));
    line.scale.x = 0.5 * style.width;
    out.markers.push_back(line);
    out.markers.push_back(
        arrow_marker(header, ns, id++, c, arc.head_start, arc.head_dir, 0.5 * style.width));
  }
  if (!glyphs.mass_centers.empty()) {
    Marker spheres =
        marker(header, "mass_centers", id++, Marker::SPHERE_LIST, style.mass_center_color);
    for (const Vec3<double>& p : glyphs.mass_centers) spheres.points.push_back(point(p));
    spheres.scale.x = spheres.scale.y = spheres.scale.z = 2 * style.sphere_radius;
    out.markers.push_back(spheres);
  }
  if (!glyphs.skeleton.empty()) {
    Marker lines = marker(header, "skeleton", id++, Marker::LINE_LIST, style.skeleton_color);
    for (const auto& s : glyphs.skeleton) {
      lines.points.push_back(point(s.first));
      lines.points.push_back(point(s.second));
    }
    lines.scale.x = 0.5 * style.width;
    out.markers.push_back(lines);
  }
  return out;
}

}  // namespace mbk_ros
