// The legend of the rviz display (mb_kinematics/viz/legend.h): every default color named as
// what it is, an entry per shown quantity, hidden ones left out, a user's color named by hue.
#include "mb_kinematics/viz/legend.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

TEST(Legend, NamesTheDefaultColors) {
  const mbk::GlyphStyle style;
  EXPECT_EQ(mbk::color_name(style.color[mbk::GlyphQuantity::kVelocity]), "cyan");
  EXPECT_EQ(mbk::color_name(style.color[mbk::GlyphQuantity::kAcceleration]), "orange");
  EXPECT_EQ(mbk::color_name(style.color[mbk::GlyphQuantity::kOmega]), "magenta");
  EXPECT_EQ(mbk::color_name(style.color[mbk::GlyphQuantity::kAlpha]), "yellow");
  EXPECT_EQ(mbk::color_name(style.mass_center_color), "white");
  EXPECT_EQ(mbk::color_name(style.skeleton_color), "white");
}

TEST(Legend, NamesAnyColorByHue) {
  EXPECT_EQ(mbk::color_name({1, 0, 0, 1}), "red");
  EXPECT_EQ(mbk::color_name({1, 0, 0.1f, 1}), "red");
  EXPECT_EQ(mbk::color_name({0, 0.8f, 0, 1}), "green");
  EXPECT_EQ(mbk::color_name({0, 0, 1, 1}), "blue");
  EXPECT_EQ(mbk::color_name({0.5f, 0.5f, 0.5f, 1}), "grey");
  EXPECT_EQ(mbk::color_name({0.05f, 0.05f, 0.1f, 1}), "black");
}

TEST(Legend, ALineForEachShownQuantity) {
  mbk::GlyphStyle style;
  std::vector<std::string> legend = mbk::glyph_legend(style);
  ASSERT_EQ(legend.size(), 5u);
  EXPECT_EQ(legend[0], "cyan: velocity of G_k, m/s");
  EXPECT_EQ(legend[1], "orange: accel. of G_k, m/s^2");
  EXPECT_EQ(legend[2], "magenta: omega_k, rad/s");
  EXPECT_EQ(legend[3], "yellow: alpha_k, rad/s^2");
  EXPECT_EQ(legend[4], "white: spheres at G_k");

  style.show[mbk::GlyphQuantity::kAcceleration] = false;
  style.color[mbk::GlyphQuantity::kVelocity] = {0, 0.8f, 0, 1};
  style.mass_centers = false;
  legend = mbk::glyph_legend(style);
  ASSERT_EQ(legend.size(), 3u);
  EXPECT_EQ(legend[0], "green: velocity of G_k, m/s");
  EXPECT_EQ(legend[1].rfind("magenta:", 0), 0u) << legend[1];
}

// Each entry is a status row of rviz's Displays panel: its text (after "<color>: ") fits the
// panel's text column whole.
TEST(Legend, EveryTextFitsAStatusRow) {
  for (const std::string& entry : mbk::glyph_legend(mbk::GlyphStyle())) {
    const std::size_t colon = entry.find(": ");
    ASSERT_NE(colon, std::string::npos) << entry;
    EXPECT_LE(entry.size() - colon - 2, mbk::kMaxLegendText) << entry;
  }
}

}  // namespace
