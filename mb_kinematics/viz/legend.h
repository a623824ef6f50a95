// The legend of the glyph picture: which color is which quantity, in words, for the rviz
// display's status panel (doc/rviz.md). Colors are named by hue, so a color the user picks
// in the display's properties is named too.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk {

// "red", "orange", "yellow", "green", "cyan", "blue", "magenta"; "white", "grey", "black" for
// unsaturated colors.
std::string color_name(const Rgba& color);

// The longest text after "<color>: " in a legend entry: what the text column of rviz's Displays
// panel shows whole in the shipped configs (doc/rviz.md).
constexpr std::size_t kMaxLegendText = 21;

// An entry per shown quantity and for the mass centers, e.g. "cyan: velocity of G_k, m/s";
// the rviz display shows each as a status row (name "cyan", the text after ": ").
std::vector<std::string> glyph_legend(const GlyphStyle& style);

}  // namespace mbk
