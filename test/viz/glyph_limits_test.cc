// The picture's limits (mb_kinematics/viz/, ROS-free): far from R's origin every glyph a
// single-precision renderer gets is finite and points the right way (the rviz display's
// scene node at an anchor near the bodies, local_glyphs.h); bodies beyond kMaxGlyphDistance are
// left out and named; names of any length never reach a recursive regex; at most max_bodies
// bodies are drawn, the others counted.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mb_kinematics/viz/body_filter.h"
#include "mb_kinematics/viz/glyphs.h"
#include "mb_kinematics/viz/local_glyphs.h"

namespace {

using mbk::GlyphBody;
using mbk::Glyphs;
using mbk::GlyphStyle;
using mbk::Vec3;

GlyphBody body_at(const Vec3<double>& g, const std::string& name = "b", uint32_t k = 1) {
  GlyphBody b;
  b.name = name;
  b.index = k;
  b.origin = g - Vec3<double>(0.1, 0, 0);
  b.mass_center = g;
  b.vectors = {
      {Vec3<double>(1, 0, 0), Vec3<double>(0, 2, 0), Vec3<double>(0, 0, 3), Vec3<double>(4, 0, 1)}};
  return b;
}

// Every number the renderer is given for `glyphs`, relative to their anchor: finite; arrows of
// the glyph's length and direction.
void expect_finite_locally(const Glyphs& glyphs, const std::string& where) {
  const Vec3<double> anchor = mbk::glyph_anchor(glyphs);
  ASSERT_TRUE(anchor.allFinite()) << where;
  for (const mbk::GlyphArrow& a : glyphs.arrows) {
    const auto local = mbk::local_arrow(a.start, a.vector, anchor);
    ASSERT_TRUE(local.has_value()) << where;
    EXPECT_TRUE(local->start.allFinite() && local->direction.allFinite()) << where;
    EXPECT_NEAR(local->direction.norm(), 1, 1e-6) << where;
    EXPECT_LT((local->direction.cast<double>() - a.vector.normalized()).norm(), 1e-6) << where;
    EXPECT_NEAR(local->length, a.vector.norm(), 1e-6 * a.vector.norm()) << where;
  }
  for (const mbk::GlyphArc& arc : glyphs.arcs) {
    for (const Vec3<double>& p : arc.points)
      EXPECT_TRUE(mbk::local_point(p, anchor).allFinite()) << where;
    EXPECT_TRUE(mbk::local_arrow(arc.head_start, arc.head_dir, anchor).has_value()) << where;
  }
  for (const Vec3<double>& g : glyphs.mass_centers)
    EXPECT_TRUE(mbk::local_point(g, anchor).allFinite()) << where;
}

// A robot at UTM coordinates, bodies at 1e7 m and beyond, and near and far bodies together.
TEST(GlyphLimits, FarBodiesGiveFiniteArrowsPointingTheRightWay) {
  GlyphStyle style;
  style.skeleton = true;
  for (const Vec3<double>& g :
       {Vec3<double>(500000, 5000000, 0), Vec3<double>(1e7, 0, 0), Vec3<double>(0, -3e9, 2),
        Vec3<double>(1e12, 1e12, 1e12), Vec3<double>(9e14, 0, 0)}) {
    const std::vector<GlyphBody> bodies = {body_at(g, "a", 1),
                                           body_at(g + Vec3<double>(0, 0.5, 0), "b", 2)};
    const Glyphs glyphs = mbk::make_glyphs(bodies, style);
    EXPECT_EQ(glyphs.arrows.size(), 8u) << g.transpose();
    EXPECT_EQ(glyphs.mass_centers.size(), 2u);
    expect_finite_locally(glyphs, "at " + std::to_string(g.x()));
  }
  const std::vector<GlyphBody> spread = {body_at(Vec3<double>::Zero(), "near", 1),
                                         body_at(Vec3<double>(1e7, 0, 0), "far", 2)};
  expect_finite_locally(mbk::make_glyphs(spread, style), "near and far");
}

// 40 km out, an arrow of 1.5 mm: its two ends are one float apart there.
TEST(GlyphLimits, ShortArrowFarOutKeepsItsLength) {
  GlyphStyle style;
  style.scale = {{1.5e-3, 0, 0, 0}};
  const Glyphs glyphs = mbk::make_glyphs({body_at(Vec3<double>(40000, 0, 0))}, style);
  ASSERT_EQ(glyphs.arrows.size(), 1u);
  expect_finite_locally(glyphs, "40 km");
}

TEST(GlyphLimits, BeyondTheLimitLeftOutAndNamed) {
  GlyphStyle style;
  style.scale = {{1, 1, 1e-3, 1e-3}};
  std::vector<GlyphBody> bodies = {body_at(Vec3<double>(1, 2, 3), "here", 1),
                                   body_at(Vec3<double>(1e16, 0, 0), "far", 2),
                                   body_at(Vec3<double>(0, 0, 1e300), "farther", 3)};
  bodies[0].vectors[mbk::GlyphQuantity::kAcceleration] = Vec3<double>(0, 1e20, 0);
  const Glyphs glyphs = mbk::make_glyphs(bodies, style);
  EXPECT_EQ(glyphs.far, std::vector<std::string>({"far", "farther"}));
  EXPECT_EQ(glyphs.arrows.size(), 3u);  // here's, but its acceleration of 1e20 m
  EXPECT_EQ(glyphs.mass_centers.size(), 1u);
  expect_finite_locally(glyphs, "beyond");
}

TEST(GlyphLimits, LocalArrowRefusesWhatAFloatCannotHold) {
  const Vec3<double> zero = Vec3<double>::Zero();
  EXPECT_FALSE(mbk::local_arrow(zero, zero, zero).has_value());
  EXPECT_FALSE(mbk::local_arrow(zero, Vec3<double>(1e39, 0, 0), zero).has_value());
  EXPECT_FALSE(mbk::local_arrow(Vec3<double>(1e39, 0, 0), Vec3<double>(1, 0, 0), zero));
  EXPECT_TRUE(mbk::local_arrow(zero, Vec3<double>(1e-3, 0, 0), zero).has_value());
}

// The default filter on a name of 100,000 characters: a plain string test (libstdc++'s regex
// overflowed the stack at about 30,000).
TEST(GlyphLimits, LongNamesNeverReachARegex) {
  const std::string name(100000, 'a');
  const std::string massless = name + "__alpha";
  const std::vector<GlyphBody> bodies = {body_at(Vec3<double>::Zero(), name, 1),
                                         body_at(Vec3<double>::Ones(), massless, 2)};
  GlyphStyle style;
  EXPECT_EQ(mbk::selected_bodies(bodies, style), std::vector<char>({1, 0}));
  Glyphs glyphs = mbk::make_glyphs(bodies, style);
  EXPECT_EQ(glyphs.mass_centers.size(), 1u);
  EXPECT_EQ(glyphs.long_names, 0u);
  style.filter = mbk::BodyFilter("^a");  // a user's pattern: not run on the long names
  glyphs = mbk::make_glyphs(bodies, style);
  EXPECT_TRUE(glyphs.mass_centers.empty());
  EXPECT_EQ(glyphs.long_names, 2u);
  const std::string longest(mbk::kMaxFilteredName, 'a');
  EXPECT_TRUE(mbk::BodyFilter("^a").drawn(longest));
  EXPECT_FALSE(mbk::BodyFilter("^a").drawn(longest + "a"));
  EXPECT_FALSE(mbk::BodyFilter(mbk::kDefaultBodyFilter, "b").drawn(longest + "a"));
  EXPECT_TRUE(mbk::BodyFilter().drawn(longest + "a"));
  EXPECT_TRUE(mbk::BodyFilter("").drawn("x__y"));  // an empty pattern draws every name
}

TEST(GlyphLimits, AtMostMaxBodiesDrawn) {
  std::vector<GlyphBody> bodies;
  for (uint32_t k = 1; k <= 100000; ++k)
    bodies.push_back(body_at(Vec3<double>(k, 0, 0), "b" + std::to_string(k), k));
  bodies[10].mass_center.x() = std::numeric_limits<double>::quiet_NaN();
  GlyphStyle style;
  style.skeleton = true;
  Glyphs glyphs = mbk::make_glyphs(bodies, style);
  EXPECT_EQ(glyphs.mass_centers.size(), mbk::kDefaultMaxBodies);
  EXPECT_EQ(glyphs.arrows.size(), 4 * mbk::kDefaultMaxBodies);
  EXPECT_LE(glyphs.skeleton.size(), mbk::kDefaultMaxBodies);
  EXPECT_EQ(glyphs.over_max_bodies, 100000 - 1 - mbk::kDefaultMaxBodies);
  EXPECT_EQ(glyphs.skipped.size(), 1u);
  EXPECT_EQ(glyphs.mass_centers.back().x(), mbk::kDefaultMaxBodies + 1);  // the first ones
  // Auto-scale follows the bodies drawn.
  bodies[50000].vectors[mbk::GlyphQuantity::kVelocity] = Vec3<double>(100, 0, 0);
  EXPECT_DOUBLE_EQ(mbk::max_norm(bodies, style, mbk::GlyphQuantity::kVelocity), 1);
  style.max_bodies = 0;
  glyphs = mbk::make_glyphs(bodies, style);
  EXPECT_TRUE(glyphs.arrows.empty() && glyphs.mass_centers.empty() && glyphs.skeleton.empty());
}

}  // namespace
