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

double heaviest(const std::vector<GlyphBody>& bodies) {
  double m = 0;
  for (const GlyphBody& b : bodies)
    if (std::isfinite(b.mass)) m = std::max(m, b.mass);
  return m;
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

void add_vectors(const GlyphBody& b, const GlyphStyle& style, Glyphs& out) {
  const Vec3<double>& g = b.mass_center;
  for (int q = 0; q < GlyphQuantity::kCount; ++q) {
    if (!style.show[q]) continue;
    const Vec3<double>& v = b.vectors[q];
    const double length = style.scale[q] * v.norm();
    if (!(length >= style.min_length && length <= kMaxGlyphDistance)) continue;
    out.arrows.push_back({q, g, length * v.normalized()});
    if (q == GlyphQuantity::kOmega || q == GlyphQuantity::kAlpha)
      out.arcs.push_back(make_arc(q, g, v, length, style));
  }
}

// Lines from each drawn body's joint point O_k to that of its nearest drawn lower body.
void add_skeleton(const std::vector<GlyphBody>& bodies, const std::vector<char>& selected,
                  const std::vector<char>& ok, Glyphs& out) {
  // Body index k -> position in bodies; a map, as k comes from the message (any uint32).
  std::unordered_map<uint32_t, int> at;
  for (size_t i = 0; i < bodies.size(); ++i) at[bodies[i].index] = static_cast<int>(i);
  auto position = [&](uint32_t k) {
    const auto it = at.find(k);
    return it == at.end() ? -1 : it->second;
  };
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!ok[i]) continue;
    int j = position(bodies[i].lower);
    for (int steps = 0; j >= 0 && !selected[j] && steps < 1000; ++steps)
      j = position(bodies[j].lower);
    if (j < 0 || !ok[j]) continue;
    const Vec3<double>& a = bodies[j].origin;
    const Vec3<double>& b = bodies[i].origin;
    if ((a - b).norm() > 1e-6) out.skeleton.emplace_back(a, b);
  }
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

std::vector<char> selected_bodies(const std::vector<GlyphBody>& bodies, const GlyphStyle& style) {
  const double min_mass = style.min_mass_fraction * heaviest(bodies);
  std::vector<char> selected(bodies.size(), 0);
  for (size_t i = 0; i < bodies.size(); ++i) {
    const GlyphBody& b = bodies[i];
    selected[i] = !(b.mass < min_mass) && style.filter.drawn(b.name);  // NaN (unknown) is kept
  }
  return selected;
}

std::vector<char> drawn_bodies(const std::vector<GlyphBody>& bodies, const GlyphStyle& style,
                               Glyphs* report) {
  const std::vector<char> selected = selected_bodies(bodies, style);
  std::vector<char> drawn(bodies.size(), 0);
  Glyphs ignored;
  Glyphs& out = report ? *report : ignored;
  size_t count = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const GlyphBody& b = bodies[i];
    if (!finite(b)) {
      out.skipped.push_back(b.name);
    } else if (!selected[i]) {
      if (style.filter.too_long(b.name)) ++out.long_names;
    } else if (!near(b)) {
      out.far.push_back(b.name);
    } else if (count == style.max_bodies) {
      ++out.over_max_bodies;
    } else {
      drawn[i] = 1;
      ++count;
    }
  }
  return drawn;
}

double max_norm(const std::vector<GlyphBody>& bodies, const GlyphStyle& style, int q) {
  const std::vector<char> drawn = drawn_bodies(bodies, style, nullptr);
  double m = 0;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (drawn[i]) m = std::max(m, bodies[i].vectors[q].norm());
  return m;
}

double AutoScale::update(double max, double length, double decay) {
  max_ = std::max(max, max_ * decay);
  return max_ > 0 ? length / max_ : 1.0;
}

Glyphs make_glyphs(const std::vector<GlyphBody>& bodies, const GlyphStyle& style) {
  Glyphs out;
  const std::vector<char> drawn = drawn_bodies(bodies, style, &out);
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!drawn[i]) continue;
    add_vectors(bodies[i], style, out);
    if (style.mass_centers) out.mass_centers.push_back(bodies[i].mass_center);
  }
  if (style.skeleton) add_skeleton(bodies, selected_bodies(bodies, style), drawn, out);
  return out;
}

}  // namespace mbk
