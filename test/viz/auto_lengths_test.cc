// Auto lengths of the picture (mb_kinematics/viz/auto_lengths.h, ROS-free), on two robots of
// test/robots/ of different sizes (Solo 12, 0.58 m, and Romeo, 1.56 m: the diagonal of the box
// around their joint points and mass centers) moving every joint: each quantity's longest arrow
// is Length Fraction of the robot's size, on both robots and for angular and linear quantities
// alike; a few messages' spikes do not shrink the other arrows and are drawn at most kAutoCap
// times as long; a larger motion is followed within the window; a robot twice as large moving
// alike is drawn twice as large; the hostile scene of the rviz tests (10,000 bodies far from R's
// origin, the first Max Bodies of them drawn a few centimetres large) shows every quantity's
// arrows clear of the mass-center spheres; a value whose norm overflows leaves the scales finite.
#include "mb_kinematics/viz/auto_lengths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/io/urdf_model.h"

namespace {

using mbk::GlyphBody;
using mbk::GlyphQuantity;
using mbk::GlyphStyle;
using mbk::Vec3;

constexpr double kRate = 50;  // messages per second, as demo.launch's

// The bodies of `model` at time t (s) of a smooth motion of every coordinate, `gain` times
// the amplitude: q_i = gain 0.4 sin(w_i t + i), w_i = 1 + 0.1 i rad/s, its exact derivatives.
std::vector<GlyphBody> bodies_at(const mbk::Model& model, double t, double gain = 1) {
  mbk::JointState<double> state(model);
  for (int i = 0; i < model.nv; ++i) {
    const double w = 1 + 0.1 * i, a = gain * 0.4;
    state.position[i] = a * std::sin(w * t + i);
    state.velocity[i] = a * w * std::cos(w * t + i);
    state.acceleration[i] = -a * w * w * std::sin(w * t + i);
  }
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  std::vector<GlyphBody> bodies(model.body_count());
  for (int k = 1; k <= model.body_count(); ++k) {
    GlyphBody& b = bodies[k - 1];
    b.name = model.bodies[k].name;
    b.index = k;
    b.lower = model.bodies[k].lower;
    b.origin = data.origin[k];
    b.orientation = Eigen::Quaterniond(data.rotation[k]);
    b.mass_center = data.mass_center[k];
    b.mass = model.bodies[k].mass;
    b.vectors[GlyphQuantity::kVelocity] = data.mass_center_velocity[k];
    b.vectors[GlyphQuantity::kAcceleration] = data.mass_center_acceleration[k];
    b.vectors[GlyphQuantity::kOmega] = data.omega[k];
    b.vectors[GlyphQuantity::kAlpha] = data.alpha[k];
  }
  return bodies;
}

mbk::Model robot(const std::string& name) {
  mbk::Model model = mbk::load_urdf_file(MBK_SOURCE_DIR "/test/robots/" + name + ".urdf");
  EXPECT_EQ(model.nq, model.nv) << name;  // bodies_at's motion: no Euler parameters
  return model;
}

// The longest arrow of quantity q drawn of `bodies` with `style`.
double longest_arrow(const std::vector<GlyphBody>& bodies, const GlyphStyle& style, int q) {
  double longest = 0;
  for (const mbk::GlyphArrow& a : mbk::make_glyphs(bodies, style).arrows)
    if (a.quantity == q) longest = std::max(longest, a.vector.norm());
  return longest;
}

TEST(AutoLengths, RobotSizeIsTheDiagonalOfTheBoxOfJointPointsAndMassCenters) {
  GlyphBody a, b;
  a.origin = {0, 0, 0};
  a.mass_center = {0.1, 0, 0};
  b.origin = {0, 0.2, 0};
  b.mass_center = {0, 0.1, -0.4};
  EXPECT_NEAR(mbk::robot_size({a, b}), std::sqrt(0.01 + 0.04 + 0.16), 1e-15);
  EXPECT_EQ(mbk::robot_size({}), 0);
  EXPECT_EQ(mbk::robot_size({GlyphBody()}), 0);  // a point: AutoLengths keeps its size
  EXPECT_NEAR(mbk::robot_size(bodies_at(robot("solo12"), 0, 0)), 0.583, 5e-4);
  EXPECT_NEAR(mbk::robot_size(bodies_at(robot("romeo_small"), 0, 0)), 1.564, 5e-4);
}

// Over 20 s of motion of every joint (the first seconds filling the window), each quantity's
// longest arrow is within 0.4 to 1.2 of Length Fraction (0.4) times the robot's size in 8 of 10
// messages or more, never more than kAutoCap times, and 0.6 to 1.0 of it on average: on the 0.58 m
// quadruped and on the 1.56 m humanoid, for the velocity and acceleration of G_k as for omega_k
// and alpha_k. (Measured after the first 5 s: medians 0.82 to 0.90, 90th percentiles 1.11 to
// 1.16, largest 1.83, means 0.88 to 0.95. 0.3 m for every robot draws the longest arrow at most
// 0.48 times that on Romeo, and up to 1.29 times on Solo 12.)
TEST(AutoLengths, LongestArrowIsAFractionOfTheRobotOnRobotsOfTwoSizes) {
  for (const std::string name : {"solo12", "romeo_small"}) {
    const mbk::Model model = robot(name);
    mbk::AutoLengths lengths;
    GlyphStyle style;
    style.min_mass_fraction = 0;
    double largest_size = 0;  // of the messages so far
    std::array<int, GlyphQuantity::kCount> within{};
    std::array<double, GlyphQuantity::kCount> sum{};
    const int n = static_cast<int>(20 * kRate);
    for (int i = 0; i < n; ++i) {
      const double t = i / kRate;
      const std::vector<GlyphBody> bodies = bodies_at(model, t);
      lengths.update(t, mbk::select_bodies(bodies, style), mbk::kDefaultLengthFraction, style);
      const double size = mbk::robot_size(bodies);  // the box changes with the posture
      largest_size = std::max(largest_size, size);
      ASSERT_GE(lengths.size(), size) << name;
      ASSERT_LE(lengths.size(), largest_size) << name;
      const double target = mbk::kDefaultLengthFraction * lengths.size();
      for (int q = 0; q < GlyphQuantity::kCount; ++q) {
        const double ratio = longest_arrow(bodies, style, q) / target;
        ASSERT_LE(ratio, mbk::kAutoCap * (1 + 1e-12))
            << name << " " << mbk::glyph_quantity_name(q) << " t " << t;
        within[q] += ratio >= 0.4 && ratio <= 1.2;
        sum[q] += ratio;
      }
    }
    for (int q = 0; q < GlyphQuantity::kCount; ++q) {
      EXPECT_GE(within[q], 0.8 * n) << name << " " << mbk::glyph_quantity_name(q);
      EXPECT_GE(sum[q] / n, 0.6) << name << " " << mbk::glyph_quantity_name(q);
      EXPECT_LE(sum[q] / n, 1.0) << name << " " << mbk::glyph_quantity_name(q);
    }
  }
}

// One message of ten times the motion (a spike, as an estimator's outlier) leaves the scale of
// the others as it was, and its arrows are drawn kAutoCap times the longest length.
TEST(AutoLengths, ASpikeNeitherShrinksTheOthersNorGrowsBeyondTheCap) {
  const mbk::Model model = robot("romeo_small");
  mbk::AutoLengths lengths;
  GlyphStyle style;
  style.min_mass_fraction = 0;
  double t = 0;
  for (; t < 3; t += 1 / kRate)
    lengths.update(t, mbk::select_bodies(bodies_at(model, t), style), 0.3, style);
  const auto before = style.scale;
  std::vector<GlyphBody> spike = bodies_at(model, t);
  for (GlyphBody& b : spike)
    for (Vec3<double>& v : b.vectors) v *= 10;
  lengths.update(t, mbk::select_bodies(spike, style), 0.3, style);
  for (int q = 0; q < GlyphQuantity::kCount; ++q)
    EXPECT_NEAR(longest_arrow(spike, style, q), mbk::kAutoCap * 0.3 * lengths.size(), 1e-12);
  t += 1 / kRate;
  lengths.update(t, mbk::select_bodies(bodies_at(model, t), style), 0.3, style);
  for (int q = 0; q < GlyphQuantity::kCount; ++q)
    EXPECT_NEAR(style.scale[q], before[q], 0.05 * before[q]) << mbk::glyph_quantity_name(q);
}

// Every value doubles: once the window (kAutoWindow s) holds only the doubled values, of the
// same phases of the motion as before, every scale is half what it was.
TEST(AutoLengths, FollowsALargerMotionWithinTheWindow) {
  const mbk::Model model = robot("solo12");
  mbk::AutoLengths lengths;
  GlyphStyle style;
  style.min_mass_fraction = 0;
  const double step = 1 / kRate, end = 10, shift = mbk::kAutoWindow + 0.1;
  int i = 0;
  for (; i * step <= end; ++i)
    lengths.update(i * step, mbk::select_bodies(bodies_at(model, i * step), style), 0.3, style);
  const auto before = style.scale;
  for (; i * step <= end + shift; ++i) {
    std::vector<GlyphBody> bodies = bodies_at(model, i * step - shift);
    for (GlyphBody& b : bodies)
      for (Vec3<double>& v : b.vectors) v *= 2;
    lengths.update(i * step, mbk::select_bodies(bodies, style), 0.3, style);
  }
  for (int q = 0; q < GlyphQuantity::kCount; ++q)
    EXPECT_NEAR(style.scale[q], 0.5 * before[q], 0.02 * before[q]) << mbk::glyph_quantity_name(q);
}

// A robot twice as large, moving alike (its linear quantities twice as large, its angular ones
// the same), is drawn twice as large: every arrow twice as long.
TEST(AutoLengths, ARobotTwiceAsLargeIsDrawnTwiceAsLarge) {
  const mbk::Model model = robot("solo12");
  mbk::AutoLengths small, large;
  GlyphStyle small_style, large_style;
  small_style.min_mass_fraction = large_style.min_mass_fraction = 0;
  small_style.min_length = 1e-9;  // the same arrows left out of both
  large_style.min_length = 2e-9;
  for (double t = 0; t < 6; t += 1 / kRate) {
    const std::vector<GlyphBody> bodies = bodies_at(model, t);
    std::vector<GlyphBody> twice = bodies;
    for (GlyphBody& b : twice) {
      b.origin *= 2;
      b.mass_center *= 2;
      b.vectors[GlyphQuantity::kVelocity] *= 2;
      b.vectors[GlyphQuantity::kAcceleration] *= 2;
    }
    small.update(t, mbk::select_bodies(bodies, small_style), 0.3, small_style);
    large.update(t, mbk::select_bodies(twice, large_style), 0.3, large_style);
    const mbk::Glyphs a = mbk::make_glyphs(bodies, small_style);
    const mbk::Glyphs b = mbk::make_glyphs(twice, large_style);
    ASSERT_EQ(a.arrows.size(), b.arrows.size()) << t;
    for (size_t i = 0; i < a.arrows.size(); ++i)
      ASSERT_NEAR(b.arrows[i].vector.norm(), 2 * a.arrows[i].vector.norm(), 1e-12) << t;
  }
}

// An arc's radius grows with its arrow, a third of its length, up to Arc Radius: small rotations
// do not wear large arcs beside the linear arrows.
TEST(AutoLengths, ArcsGrowWithTheirArrowUpToArcRadius) {
  GlyphBody b;
  b.vectors = {
      {Vec3<double>::Zero(), Vec3<double>::Zero(), Vec3<double>(0, 0, 1), Vec3<double>(0, 0, 10)}};
  GlyphStyle style;
  style.scale = {{1, 1, 0.06, 0.06}};
  const mbk::Glyphs g = mbk::make_glyphs({b}, style);
  ASSERT_EQ(g.arcs.size(), 2u);
  const Vec3<double> center_omega(0, 0, 0.03), center_alpha(0, 0, 0.3);
  EXPECT_NEAR((g.arcs[0].points[0] - center_omega).norm(), 0.02, 1e-12);  // 0.06 m / 3
  EXPECT_NEAR((g.arcs[1].points[0] - center_alpha).norm(), style.arc_radius, 1e-12);
}

// test/rviz/hostile_bodies.py's message (rviz_hostile_many): `n` bodies in a ring of 1 m diameter
// around UTM coordinates (x 500000, y 5000000), their joint points at z 0.5 and mass centers at
// 0.6, velocity and acceleration of norm 1 (along and across the ring), omega_k 1 + 0.1 k about
// z, alpha_k 1 about x; masses unknown.
std::vector<GlyphBody> hostile_ring(int n) {
  std::vector<GlyphBody> bodies(n);
  for (int k = 0; k < n; ++k) {
    GlyphBody& b = bodies[k];
    const double angle = 2 * M_PI * k / n, c = std::cos(angle), s = std::sin(angle);
    b.name = "body" + std::to_string(k);
    b.index = k + 1;
    b.lower = k;
    b.origin = {500000 + 0.5 * c, 5000000 + 0.5 * s, 0.5};
    b.mass_center = {b.origin.x(), b.origin.y(), 0.6};
    b.vectors = {{Vec3<double>(-s, c, 0), Vec3<double>(-c, -s, 0), Vec3<double>(0, 0, 1 + 0.1 * k),
                  Vec3<double>(1, 0, 0)}};
  }
  return bodies;
}

// The hostile scene at its 5 Hz for 10 s: the first Max Bodies (100) of the 10,000 bodies are
// drawn, an arc of 3 cm of the ring (the robot's size 0.105 m). Each quantity's longest arrow
// reaches a sphere radius or more past every mass-center sphere drawn (its tip at least two
// radii from each G_k), and no arrow is longer than kAutoCap times auto_longest. (With 0.4 of
// the robot's size alone, the longest arrows were 0.042 m, inside the row of spheres of radius
// 0.035 m: the velocity arrows, which run along the row, showed no pixel in rviz.)
TEST(AutoLengths, HostileManyBodiesShowEveryQuantityClearOfTheSpheres) {
  const std::vector<GlyphBody> bodies = hostile_ring(10000);
  mbk::AutoLengths lengths;
  GlyphStyle style;
  for (double t = 0; t < 10; t += 0.2)
    lengths.update(t, mbk::select_bodies(bodies, style), mbk::kDefaultLengthFraction, style);
  const mbk::BodySelection drawn = mbk::select_bodies(bodies, style);
  ASSERT_EQ(drawn.drawn().size(), style.max_bodies);
  EXPECT_NEAR(lengths.size(), 0.105, 5e-4);
  const double longest = mbk::auto_longest(mbk::kDefaultLengthFraction, lengths.size(), style);
  const mbk::Glyphs glyphs = mbk::make_glyphs(drawn, style);
  std::array<double, GlyphQuantity::kCount> clearance{};  // of each quantity's farthest tip
  for (const mbk::GlyphArrow& a : glyphs.arrows) {
    ASSERT_LE(a.vector.norm(), mbk::kAutoCap * longest * (1 + 1e-12));
    double nearest = INFINITY;  // the tip's distance to the nearest G_k
    for (const GlyphBody& b : drawn.drawn())
      nearest = std::min(nearest, (a.start + a.vector - b.mass_center).norm());
    clearance[a.quantity] = std::max(clearance[a.quantity], nearest);
  }
  for (int q = 0; q < GlyphQuantity::kCount; ++q)
    EXPECT_GE(clearance[q], 2 * style.sphere_radius) << mbk::glyph_quantity_name(q);
}

// A body whose velocity's norm overflows a double (components of 1e200, finite) beside bodies
// moving at 1 m/s: the velocity scale stays finite and non-zero, so that the other bodies'
// velocity arrows are still drawn (a scale of 0, longest / infinity, left none).
TEST(AutoLengths, AnOverflowingNormLeavesTheOtherArrowsDrawn) {
  std::vector<GlyphBody> bodies = hostile_ring(40);
  bodies[0].vectors[GlyphQuantity::kVelocity] = {1e200, 1e200, 0};
  mbk::AutoLengths lengths;
  GlyphStyle style;
  for (double t = 0; t < 2; t += 0.1)
    lengths.update(t, mbk::select_bodies(bodies, style), mbk::kDefaultLengthFraction, style);
  const double scale = style.scale[GlyphQuantity::kVelocity];
  EXPECT_TRUE(std::isfinite(scale) && scale > 0) << scale;
  int velocity_arrows = 0;
  for (const mbk::GlyphArrow& a : mbk::make_glyphs(bodies, style).arrows)
    velocity_arrows += a.quantity == GlyphQuantity::kVelocity;
  EXPECT_EQ(velocity_arrows, 39);
}

// The quantile of a window, by partial sorting: the oracle of RunningQuantile.
double sorted_quantile(std::vector<double> window, double quantile) {
  const size_t n = window.size();
  const auto at =
      window.begin() + static_cast<std::ptrdiff_t>(std::min(
                           n - 1, static_cast<size_t>(std::max(0.0, std::ceil(quantile * n) - 1))));
  std::nth_element(window.begin(), at, window.end());
  return *at;
}

// RunningQuantile equals the sorted window's quantile at every update: values with many ties
// (a few distinct levels), windows that slide by time and by the kMaxValues cap, a time going
// back (a bag played again: starts over), infinities and NaN (counted as +inf).
TEST(RunningQuantile, EqualsTheSortedWindowAtEveryUpdate) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const double step : {0.002, 0.0002})  // the second fills the cap
    for (const double quantile : {0.0, 0.5, 0.75, 1.0}) {
      mbk::RunningQuantile running(2.0, quantile);
      std::vector<std::pair<double, double>> window;
      double time = 0;
      for (int i = 0; i < 6000; ++i) {
        const double u = unit(rng);
        time = u < 0.0002 ? time - 1 : time + (u < 0.3 ? 0.0 : step * (0.2 + unit(rng)));
        double value = std::floor(8 * unit(rng)) / 4;  // ties
        if (u > 0.995) value = std::numeric_limits<double>::infinity();
        if (u > 0.998) value = std::nan("");
        if (!window.empty() && time < window.back().first) window.clear();
        window.emplace_back(time,
                            std::isnan(value) ? std::numeric_limits<double>::infinity() : value);
        while (window.size() > mbk::RunningQuantile::kMaxValues ||
               window.front().first < time - 2.0)
          window.erase(window.begin());
        std::vector<double> values;
        for (const auto& v : window) values.push_back(v.second);
        ASSERT_EQ(running.update(time, value), sorted_quantile(values, quantile))
            << "quantile " << quantile << ", update " << i << ", " << values.size() << " values";
      }
    }
}

}  // namespace
