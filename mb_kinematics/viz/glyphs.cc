#include "mb_kinematics/viz/glyphs.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace mbk {
namespace {

constexpr int kArcSegments = 24;
constexpr double kArcSweep = 1.5 * M_PI;  // 3/4 of a turn

bool finite(const GlyphBody& b) {
  bool ok = b.origin.allFinite() && b.mass_center.allFinite() && b.orientation.coeffs().allFinite();
  for (const Vec3<double>& v : b.vectors) ok = ok && v.allFinite();
  return ok;
}

bool near(const GlyphBody& b) {
  return b.origin.lpNorm<Eigen::Infinity>() <= kMaxGlyphDistance &&
         b.mass_center.lpNorm<Eigen::Infinity>() <= kMaxGlyphDistance;
}

// A 3/4 arc about the arrow's axis, centred half-way along it, turning the right-hand way; its
// radius grows with the arrow up to the style's (a short arrow does not wear a large arc).
GlyphArc make_arc(int q, const Vec3<double>& start, const Vec3<double>& v, double length,
                  const GlyphStyle& style) {
  GlyphArc arc;
  arc.quantity = q;
  const Vec3<double> n = v.normalized();
  const Vec3<double> u = n.unitOrthogonal(), w = n.cross(u);
  const Vec3<double> center = start + 0.5 * length * n;
  const double r = std::min(style.arc_radius, length / 3);
  for (int i = 0; i <= kArcSegments; ++i) {
    const double t = kArcSweep * i / kArcSegments;
    arc.points.push_back(center + r * (std::cos(t) * u + std::sin(t) * w));
  }
  const Vec3<double> tangent = -std::sin(kArcSweep) * u + std::cos(kArcSweep) * w;
  arc.head_start = arc.points.back();
  arc.head_dir = 3 * style.width * tangent;
  return arc;
}

void add_vectors(const GlyphBody& b, const GlyphStyle& style, Glyphs& out) {
  const Vec3<double>& g = b.mass_center;
  for (int q = 0; q < GlyphQuantity::kCount; ++q) {
    if (!style.show[q]) continue;
    const Vec3<double>& v = b.vectors[q];
    const double scaled = style.scale[q] * v.norm();
    if (!(scaled >= style.min_length && scaled <= kMaxGlyphDistance)) continue;
    const double length = std::min(scaled, style.max_length);
    out.arrows.push_back({q, g, length * v.normalized()});
    if (q == GlyphQuantity::kOmega || q == GlyphQuantity::kAlpha)
      out.arcs.push_back(make_arc(q, g, v, length, style));
  }
}

// Whether `b` (named `name`) is selected: drawn by the filter and not lighter than `min_mass`
// (an unknown mass, NaN, is kept).
bool selected(const std::string& name, const GlyphBody& b, const GlyphStyle& style,
              double min_mass) {
  return !(b.mass < min_mass) && style.filter.drawn(name);
}

}  // namespace

const char* glyph_quantity_name(int q) {
  switch (static_cast<GlyphQuantity::Index>(q)) {
    case GlyphQuantity::kVelocity:
      return "velocity";
    case GlyphQuantity::kAcceleration:
      return "acceleration";
    case GlyphQuantity::kOmega:
      return "omega";
    case GlyphQuantity::kAlpha:
      return "alpha";
    case GlyphQuantity::kCount:
      break;
  }
  return "?";
}

double heaviest(const std::vector<GlyphBody>& bodies) {
  double m = 0;
  for (const GlyphBody& b : bodies)
    if (std::isfinite(b.mass)) m = std::max(m, b.mass);
  return m;
}

std::vector<char> selected_bodies(const std::vector<GlyphBody>& bodies, const GlyphStyle& style) {
  const double min_mass = style.min_mass_fraction * heaviest(bodies);
  std::vector<char> out(bodies.size(), 0);
  for (size_t i = 0; i < bodies.size(); ++i)
    out[i] = selected(bodies[i].name, bodies[i], style, min_mass);
  return out;
}

BodySelection::BodySelection(const GlyphStyle& style, double heaviest)
    : style_(style), min_mass_(style.min_mass_fraction * heaviest) {}

void BodySelection::add(const std::string& name, const GlyphBody& body) {
  const bool chosen = selected(name, body, style_, min_mass_);
  bool drawn = false;
  if (!finite(body)) {
    report_.skipped.push_back(name);
  } else if (!chosen) {
    if (style_.filter.too_long(name)) ++report_.long_names;
  } else if (!near(body)) {
    report_.far.push_back(name);
  } else if (drawn_.size() >= style_.max_bodies) {
    ++report_.over_max_bodies;
  } else {
    drawn = true;
    drawn_.push_back(body);
    drawn_.back().name = name;
  }
  if (style_.skeleton)
    links_.push_back({body.index, body.lower, chosen, drawn ? int(drawn_.size()) - 1 : -1});
}

// Body index k -> position in the message; a map, as k comes from the message (any uint32).
std::vector<std::pair<Vec3<double>, Vec3<double>>> BodySelection::skeleton() const {
  std::unordered_map<uint32_t, int> at;
  for (size_t i = 0; i < links_.size(); ++i) at[links_[i].index] = static_cast<int>(i);
  auto position = [&](uint32_t k) {
    const auto it = at.find(k);
    return it == at.end() ? -1 : it->second;
  };
  std::vector<std::pair<Vec3<double>, Vec3<double>>> out;
  for (const Link& link : links_) {
    if (link.drawn < 0) continue;
    int j = position(link.lower);
    for (int steps = 0; j >= 0 && !links_[j].selected && steps < 1000; ++steps)
      j = position(links_[j].lower);
    if (j < 0 || links_[j].drawn < 0) continue;
    const Vec3<double>& a = drawn_[links_[j].drawn].origin;
    const Vec3<double>& b = drawn_[link.drawn].origin;
    if ((a - b).norm() > 1e-6) out.emplace_back(a, b);
  }
  return out;
}

BodySelection select_bodies(const std::vector<GlyphBody>& bodies, const GlyphStyle& style) {
  BodySelection selection(style, heaviest(bodies));
  for (const GlyphBody& b : bodies) selection.add(b.name, b);
  return selection;
}

double max_norm(const BodySelection& selection, int q) {
  double m = 0;
  for (const GlyphBody& b : selection.drawn()) m = std::max(m, b.vectors[q].norm());
  return m;
}

double max_norm(const std::vector<GlyphBody>& bodies, const GlyphStyle& style, int q) {
  return max_norm(select_bodies(bodies, style), q);
}

Glyphs make_glyphs(const BodySelection& selection, const GlyphStyle& style) {
  Glyphs out = selection.report();
  for (const GlyphBody& b : selection.drawn()) {
    add_vectors(b, style, out);
    if (style.mass_centers) out.mass_centers.push_back(b.mass_center);
  }
  if (style.skeleton) out.skeleton = selection.skeleton();
  return out;
}

Glyphs make_glyphs(const std::vector<GlyphBody>& bodies, const GlyphStyle& style) {
  return make_glyphs(select_bodies(bodies, style), style);
}

}  // namespace mbk
