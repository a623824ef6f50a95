// The picture of the kinematics of every body, shared by the rviz display (mb_kinematics/rviz/)
// and the node's MarkerArray (~publish_markers, mb_kinematics/ros/kinematics_markers.h): per
// body an arrow for the mass-center velocity and acceleration at G_k, an arrow plus a 3/4
// circular arc (right-hand sense, with a small head) for omega and alpha, a sphere at G_k, and
// the skeleton (lines between joint points O_k). Plain geometry (Eigen), no ROS: the display
// draws it with Ogre, the node as Markers.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mb_kinematics/core/types.h"
#include "mb_kinematics/viz/body_filter.h"

namespace mbk {

// The vectors drawn, an index into GlyphStyle's arrays; scoped (GlyphQuantity::kOmega) so they
// cannot be mistaken for the analysis' ErrorQuantity. Velocity and acceleration: of G_k.
struct GlyphQuantity {
  enum Index { kVelocity, kAcceleration, kOmega, kAlpha, kCount };
};
const char* glyph_quantity_name(int q);  // "velocity", "acceleration", "omega", "alpha"

// The default of GlyphStyle::min_mass_fraction (doc/rviz.md: what it leaves out on real robots).
constexpr double kDefaultMinMassFraction = 0.005;
// The default of GlyphStyle::max_bodies (doc/rviz.md#limits): more than the robots of
// test/robots draw (at most 82 links); a renderer holds some ten objects per body drawn, and
// under software rendering (Mesa's llvmpipe) rviz's frame time, and with it how soon rviz
// answers SIGINT, grows with them: at 500 bodies a frame took 1.7-2.9 s on a loaded 2-core
// machine, at 100 rviz is out within a second.
constexpr size_t kDefaultMaxBodies = 100;
// Bodies farther than this (m) from R's origin in some coordinate, and arrows longer than it,
// are not drawn: their squares near the largest float, where a renderer's bounds overflow.
constexpr double kMaxGlyphDistance = 1e15;

struct Rgba {
  float r, g, b, a;
};

// The defaults are distinct hues (the rviz screenshot test counts their pixels): velocity
// cyan, acceleration orange, omega magenta, alpha yellow; mass centers white.
struct GlyphStyle {
  std::array<bool, GlyphQuantity::kCount> show{{true, true, true, true}};
  std::array<double, GlyphQuantity::kCount> scale{{0.1, 0.02, 0.05, 0.005}};  // m per unit
  std::array<Rgba, GlyphQuantity::kCount> color{{{0.0f, 0.8f, 1.0f, 1.0f},
                                                 {1.0f, 0.5f, 0.0f, 1.0f},
                                                 {0.9f, 0.0f, 0.9f, 1.0f},
                                                 {1.0f, 0.9f, 0.0f, 1.0f}}};
  Rgba mass_center_color{1.0f, 1.0f, 1.0f, 1.0f};
  Rgba skeleton_color{0.85f, 0.85f, 0.85f, 1.0f};
  bool mass_centers = true, skeleton = false;
  double width = 0.012;          // arrow shaft diameter (m); heads, arcs and lines follow it
  double arc_radius = 0.05;      // m, the largest (an arc's is at most its arrow's length / 3)
  double sphere_radius = 0.035;  // m
  double min_length = 1e-3;      // arrows shorter than this (m) are left out
  double max_length = kMaxGlyphDistance;  // longer arrows are drawn this long (m), their way
  BodyFilter filter;             // bodies drawn by name (the default: names without "__")
  // Bodies lighter than this fraction of the heaviest body (of those with a
  // known mass) are left out (sensor frames,
  // fingers, dummy links: their glyphs crowd the heavy bodies' without telling more).
  double min_mass_fraction = kDefaultMinMassFraction;
  // At most this many bodies drawn (the first ones of the message that pass the rest); the
  // others are counted in Glyphs::over_max_bodies.
  size_t max_bodies = kDefaultMaxBodies;
};

// One body's kinematics as drawn, everything in R.
struct GlyphBody {
  std::string name;
  uint32_t index = 0, lower = 0;                                    // k and L(k)
  Vec3<double> origin = Vec3<double>::Zero();                       // O_k
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // S0K (checked finite)
  Vec3<double> mass_center = Vec3<double>::Zero();                  // G_k
  double mass = std::numeric_limits<double>::quiet_NaN();   // kg; NaN: unknown, never left out
  std::array<Vec3<double>, GlyphQuantity::kCount> vectors;  // by GlyphQuantity
};

// `vector` goes from `start` to the tip: the scaled quantity itself, never the difference of
// two far points (which rounds to zero far from R's origin).
struct GlyphArrow {
  int quantity;
  Vec3<double> start, vector;
};
struct GlyphArc {  // a polyline, and the head at its end (from head_start along head_dir)
  int quantity;
  std::vector<Vec3<double>> points;
  Vec3<double> head_start, head_dir;
};

struct Glyphs {
  std::vector<GlyphArrow> arrows;
  std::vector<GlyphArc> arcs;
  std::vector<Vec3<double>> mass_centers;
  std::vector<std::pair<Vec3<double>, Vec3<double>>> skeleton;
  std::vector<std::string> skipped;  // bodies with a non-finite value: left out
  std::vector<std::string> far;      // bodies beyond kMaxGlyphDistance: left out
  size_t long_names = 0;             // bodies left out as too long for the filter's patterns
  size_t over_max_bodies = 0;        // bodies left out by GlyphStyle::max_bodies
};

// The bodies drawn of a message, chosen body after body in the message's order in one pass:
// selected (selected_bodies), finite, within kMaxGlyphDistance and among the first max_bodies of
// those. Only the drawn bodies are kept (at most max_bodies), so that everything after the pass
// (auto-scale, glyphs, camera framing) works on the bodies drawn, not on the message's; what is
// left out is counted in report()'s skipped, far, long_names and over_max_bodies.
class BodySelection {
 public:
  // `heaviest`: the largest known mass of the message's bodies (0 if none known). `style` must
  // outlive the selection.
  BodySelection(const GlyphStyle& style, double heaviest);
  // The next body: its values in `body` (mass NaN if unknown), its name in `name` (body.name is
  // not read: a caller can fill one GlyphBody for every body and copy names only of those kept).
  void add(const std::string& name, const GlyphBody& body);
  const std::vector<GlyphBody>& drawn() const { return drawn_; }
  const Glyphs& report() const { return report_; }
  // Lines from each drawn body's joint point O_k to that of its nearest drawn lower body (through
  // bodies not selected; GlyphStyle::skeleton must have been set for add() to keep the chain).
  std::vector<std::pair<Vec3<double>, Vec3<double>>> skeleton() const;

 private:
  struct Link {  // every body's place in the chain, for the skeleton
    uint32_t index, lower;
    bool selected;
    int drawn;  // its position in drawn_, -1 if not drawn
  };
  const GlyphStyle& style_;
  double min_mass_;
  std::vector<GlyphBody> drawn_;
  Glyphs report_;
  std::vector<Link> links_;
};

// BodySelection over `bodies`, every one with its name and mass.
BodySelection select_bodies(const std::vector<GlyphBody>& bodies, const GlyphStyle& style);

// The largest known mass of `bodies` (0 if none known).
double heaviest(const std::vector<GlyphBody>& bodies);

// The largest |vector| of quantity q over the bodies drawn (as make_glyphs draws them).
double max_norm(const BodySelection& selection, int q);
double max_norm(const std::vector<GlyphBody>& bodies, const GlyphStyle& style, int q);

// Whether each body is selected: the filter draws its name, and it is not lighter than
// min_mass_fraction of the heaviest body. Says nothing of non-finite values, distance or
// max_bodies.
std::vector<char> selected_bodies(const std::vector<GlyphBody>& bodies, const GlyphStyle& style);

// The glyphs of the bodies drawn, with the selection's report.
Glyphs make_glyphs(const BodySelection& selection, const GlyphStyle& style);
Glyphs make_glyphs(const std::vector<GlyphBody>& bodies, const GlyphStyle& style);

}  // namespace mbk
