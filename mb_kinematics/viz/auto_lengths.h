// Auto lengths of the glyph picture (doc/rviz.md#arrow-lengths), shared by the rviz display and
// the node's markers: each quantity's longest arrow is a fixed fraction of the robot's size, on
// robots of any size, angular and linear quantities alike. The robot's size is the diagonal of
// the box around the joint points O_k and mass centers G_k drawn (its largest over the last
// kAutoWindow seconds); a quantity's range is a robust running maximum of its largest value per
// message (their kAutoQuantile quantile over the last kAutoWindow seconds), so that messages'
// spikes (an estimator's outliers: on motion capture, finite differences of light distal
// segments spike in many messages) do not shrink every other arrow, and a robot that stops after
// a fast motion has its arrows back at full length kAutoWindow seconds later; arrows above that
// range are drawn at most kAutoCap times the longest length. The longest length is never below
// what the glyphs' own sizes need to show (auto_longest): a robot drawn a few centimetres large
// (the first Max Bodies of many bodies close together) would otherwise hide its arrows inside
// its mass-center spheres.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <set>
#include <utility>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk {

constexpr double kDefaultLengthFraction = 0.4;  // the longest arrow, a fraction of the size
constexpr double kAutoWindow = 2;               // s of messages the ranges look back
constexpr double kAutoQuantile = 0.75;          // of each message's largest value, in the window
constexpr double kAutoCap = 2;                  // arrows at most this times the longest length
constexpr double kPointRobotSize = 1;           // m: the size of a robot whose box is a point
constexpr double kMinLongestRadii = 3;  // the longest arrow, at least this many sphere/arc radii

// The diagonal of the box around the joint points O_k and mass centers G_k of `bodies` (m); 0
// when that box is a point or empty (AutoLengths then keeps the size it had, at first
// kPointRobotSize).
double robot_size(const std::vector<GlyphBody>& bodies);

// The length (m) of each quantity's longest arrow on a robot of `size` (m): `fraction` of it, and
// at least kMinLongestRadii times the larger of the style's sphere_radius and arc_radius, so that
// the arrow reaches two sphere radii past its mass-center sphere and its arc has its full radius.
double auto_longest(double fraction, double size, const GlyphStyle& style);

// The `quantile` (0..1; 1: the maximum) of the values of the last `window` seconds, a value per
// time: the smallest value with at least `quantile` of them at or below it. A time before the
// previous one (a bag played again) starts over. At most kMaxValues values are kept (the
// newest), whatever the rate (and for unstamped messages, all at time 0). NaN counts as +inf.
// O(log n) an update: the window is kept split in two ordered halves at the quantile.
class RunningQuantile {
 public:
  static constexpr size_t kMaxValues = 4096;
  RunningQuantile(double window, double quantile) : window_(window), quantile_(quantile) {}
  double update(double time, double value);

 private:
  void erase(double value);
  void balance();

  double window_, quantile_;
  std::deque<std::pair<double, double>> values_;  // (time, value), oldest first
  std::multiset<double> low_, high_;  // the window's values up to the quantile's, and above
};

// The scales of the glyphs, message after message (time: the message's stamp, s).
class AutoLengths {
 public:
  AutoLengths();
  // Sets style.scale (m per unit) of every quantity, so that its robust maximum is drawn
  // auto_longest(fraction, size(), style) long, and style.max_length (kAutoCap times that). A
  // quantity whose range is zero or not finite keeps its scale (a finite one, never 0 for a
  // non-zero range).
  void update(double time, const BodySelection& drawn, double fraction, GlyphStyle& style);
  double size() const { return size_; }  // the robot's size in use (m)

 private:
  RunningQuantile sizes_;
  std::array<RunningQuantile, GlyphQuantity::kCount> ranges_;
  double size_ = kPointRobotSize;
};

}  // namespace mbk
