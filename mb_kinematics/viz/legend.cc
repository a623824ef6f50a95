#include "mb_kinematics/viz/legend.h"

#include <algorithm>

namespace mbk {
namespace {

struct NamedHue {
  double hue;  // degrees: the upper end of the name's band
  const char* name;
};
// Bands of hue (degrees) and their names; red wraps around 360.
constexpr NamedHue kHues[] = {{15, "red"},   {45, "orange"}, {70, "yellow"},   {160, "green"},
                              {200, "cyan"}, {260, "blue"},  {330, "magenta"}, {360, "red"}};

// At most kMaxLegendText characters each: one status row of the Displays panel.
const char* const kWhat[GlyphQuantity::kCount] = {"velocity of G_k, m/s", "accel. of G_k, m/s^2",
                                                  "omega_k, rad/s", "alpha_k, rad/s^2"};

double hue_degrees(double r, double g, double b, double hi, double span) {
  double h = hi == r ? (g - b) / span : hi == g ? 2 + (b - r) / span : 4 + (r - g) / span;
  h *= 60;
  return h < 0 ? h + 360 : h;
}

}  // namespace

std::string color_name(const Rgba& c) {
  const double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  if (hi < 0.2) return "black";
  if (hi - lo < 0.25 * hi) return hi > 0.8 ? "white" : "grey";
  const double hue = hue_degrees(c.r, c.g, c.b, hi, hi - lo);
  for (const NamedHue& band : kHues)
    if (hue < band.hue) return band.name;
  return "red";
}

std::vector<std::string> glyph_legend(const GlyphStyle& style) {
  std::vector<std::string> legend;
  for (int q = 0; q < GlyphQuantity::kCount; ++q)
    if (style.show[q]) legend.push_back(color_name(style.color[q]) + ": " + kWhat[q]);
  if (style.mass_centers)
    legend.push_back(color_name(style.mass_center_color) + ": spheres at G_k");
  return legend;
}

}  // namespace mbk
