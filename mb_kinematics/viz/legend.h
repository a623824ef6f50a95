// The legend of the glyph picture: which color is which quantity, in words, for the rviz
// display's status panel (doc/rviz.md). Colors are named by hue, so a color the user picks
// in the display's properties is named too.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk {

// "red", "orange", "yellow", "green", "cyan", "blue", "magenta"; "white", "grey", "black" for
// unsaturated colors.
std::string color_name(const Rgba& color);

// An entry per shown quantity and for the mass centers, e.g. "cyan: velocity of each mass
// center G_k (m/s)".
std::vector<std::string> glyph_legend(const GlyphStyle& style);

}  // namespace mbk
