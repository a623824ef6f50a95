#include "mb_kinematics/ros/kinematics_markers.h"

#include <algorithm>
#include <cmath>

namespace mbk_ros {
namespace {

using mb_kinematics_msgs::BodyKinematics;
using mb_kinematics_msgs::BodyKinematicsArray;
using mbk::Vec3;

constexpr int kArcSegments = 24;
constexpr double kArcSweep = 1.5 * M_PI;  // 3/4 of a turn

template <typename V>
Vec3<double> vec(const V& v) {
  return Vec3<double>(v.x, v.y, v.z);
}

Vec3<double> quantity(const BodyKinematics& b, int q) {
  switch (q) {
    case GlyphQuantity::kVelocity:
      return vec(b.twist.linear);
    case GlyphQuantity::kAcceleration:
      return vec(b.accel.linear);
    case GlyphQuantity::kOmega:
      return vec(b.twist.angular);
    default:
      return vec(b.accel.angular);
  }
}

bool finite(const BodyKinematics& b) {
  const auto& o = b.pose.orientation;
  bool ok = vec(b.pose.position).allFinite() && vec(b.mass_center).allFinite() &&
            std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(o.w);
  for (int q = 0; q < GlyphQuantity::kCount; ++q) ok = ok && quantity(b, q).allFinite();
  return ok;
}

bool drawn(const GlyphStyle& style, const BodyKinematics& b) {
  return std::regex_search(b.name, style.filter);
}

// A 3/4 arc about the arrow's axis, centred half-way along it, turning the right-hand way.
GlyphArc make_arc(int q, const Vec3<double>& start, const Vec3<double>& v, double length,
                  const GlyphStyle& style) {
  GlyphArc arc;
  arc.quantity = q;
  const Vec3<double> n = v.normalized();
  const Vec3<double> u = n.unitOrthogonal(), w = n.cross(u);
  const Vec3<double> center = start + 0.5 * length * n;
  const double r = style.arc_radius;
  for (int i = 0; i <= kArcSegments; ++i) {
    const double t = kArcSweep * i / kArcSegments;
    arc.points.push_back(center + r * (std::cos(t) * u + std::sin(t) * w));
  }
  const Vec3<double> tangent = -std::sin(kArcSweep) * u + std::cos(kArcSweep) * w;
  arc.head_start = arc.points.back();
  arc.head_dir = 3 * style.width * tangent;
  return arc;
}

void add_vectors(const BodyKinematics& b, const GlyphStyle& style, Glyphs& out) {
  const Vec3<double> g = vec(b.mass_center);
  for (int q = 0; q < GlyphQuantity::kCount; ++q) {
    if (!style.show[q]) continue;
    const Vec3<double> v = quantity(b, q);
    const double length = style.scale[q] * v.norm();
    if (!std::isfinite(length) || length < style.min_length) continue;
    out.arrows.push_back({q, g, g + length * v.normalized()});
    if (q == GlyphQuantity::kOmega || q == GlyphQuantity::kAlpha)
      out.arcs.push_back(make_arc(q, g, v, length, style));
  }
}

// Lines from each drawn body's joint point O_k to that of its nearest drawn lower body.
void add_skeleton(const BodyKinematicsArray& msg, const GlyphStyle& style,
                  const std::vector<char>& ok, Glyphs& out) {
  std::vector<int> at;  // body index k -> position in msg.bodies
  for (size_t i = 0; i < msg.bodies.size(); ++i) {
    const uint32_t k = msg.bodies[i].index;
    if (k >= at.size()) at.resize(k + 1, -1);
    at[k] = static_cast<int>(i);
  }
  auto position = [&](uint32_t k) { return k < at.size() ? at[k] : -1; };
  for (size_t i = 0; i < msg.bodies.size(); ++i) {
    if (!ok[i]) continue;
    int j = position(msg.bodies[i].lower_body);
    for (int steps = 0; j >= 0 && !drawn(style, msg.bodies[j]) && steps < 1000; ++steps)
      j = position(msg.bodies[j].lower_body);
    if (j < 0 || !ok[j]) continue;
    const Vec3<double> a = vec(msg.bodies[j].pose.position), b = vec(msg.bodies[i].pose.position);
    if ((a - b).norm() > 1e-6) out.skeleton.emplace_back(a, b);
  }
}

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

visualization_msgs::Marker arrow_marker(const std_msgs::Header& header, const std::string& ns,
                                        int id, const Rgba& c, const Vec3<double>& from,
                                        const Vec3<double>& to, double width) {
  visualization_msgs::Marker m = marker(header, ns, id, visualization_msgs::Marker::ARROW, c);
  m.points = {point(from), point(to)};
  m.scale.x = width;
  m.scale.y = 2 * width;
  m.scale.z = std::min(3 * width, 0.5 * (to - from).norm());
  return m;
}

}  // namespace

const char* quantity_name(int q) {
  static const char* const names[GlyphQuantity::kCount] = {"velocity", "acceleration", "omega",
                                                           "alpha"};
  return names[q];
}

double max_norm(const BodyKinematicsArray& msg, const GlyphStyle& style, int q) {
  double m = 0;
  for (const BodyKinematics& b : msg.bodies)
    if (finite(b) && drawn(style, b)) m = std::max(m, quantity(b, q).norm());
  return m;
}

double AutoScale::update(double max, double length, double decay) {
  max_ = std::max(max, max_ * decay);
  return max_ > 0 ? length / max_ : 1.0;
}

Glyphs make_glyphs(const BodyKinematicsArray& msg, const GlyphStyle& style) {
  Glyphs out;
  std::vector<char> ok(msg.bodies.size(), 0);
  for (size_t i = 0; i < msg.bodies.size(); ++i) {
    const BodyKinematics& b = msg.bodies[i];
    if (!finite(b)) {
      out.skipped.push_back(b.name);
      continue;
    }
    if (!drawn(style, b)) continue;
    ok[i] = 1;
    add_vectors(b, style, out);
    if (style.mass_centers) out.mass_centers.push_back(vec(b.mass_center));
  }
  if (style.skeleton) add_skeleton(msg, style, ok, out);
  return out;
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
    out.markers.push_back(arrow_marker(header, quantity_name(a.quantity), id++,
                                       style.color[a.quantity], a.start, a.end, style.width));
  for (const GlyphArc& arc : glyphs.arcs) {
    const std::string ns = std::string(quantity_name(arc.quantity)) + "_arc";
    const Rgba& c = style.color[arc.quantity];
    Marker line = marker(header, ns, id++, Marker::LINE_STRIP, c);
    for (const Vec3<double>& p : arc.points) line.points.push_back(point(p));
    line.scale.x = 0.5 * style.width;
    out.markers.push_back(line);
    out.markers.push_back(arrow_marker(header, ns, id++, c, arc.head_start,
                                       arc.head_start + arc.head_dir, 0.5 * style.width));
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
