// A BVH recording's whole motion against a human's, so that a misread file is said, not plotted:
// the standing height in the frames (not the rest pose only), the whole-body mass center's
// height above the lowest joint and its horizontal speed against the pelvis's. ROS-free.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/bvh.h"

namespace mbk {

// Of the moving skeleton: every body but those fixed in space while others move (a static ROOT
// such as Bandai Namco's joint_Root, metres from the walker it would otherwise take in).
struct MotionFigures {
  int up = 1;                     // the axis of R that is up: along which the skeleton is tallest
  double rest_height = 0;         // m, the rest pose's joints' extent along `up`
  double height = 0;              // m, the median over the frames of the same
  double mass_center_height = 0;  // m, median over the frames, above the frame's lowest joint
  double mass_center_speed = 0;   // m/s, horizontal: path length (every 0.1 s) over duration
  double root_speed = 0;          // m/s, likewise of the first body that moves (the pelvis)
  bool has_mass = false;
};

// The figures over the frames of `bvh` (at most about 1000 of them, evenly spaced), for
// `model` (model_from_bvh of it with `scale`, masses set or not).
MotionFigures motion_figures(const BvhFile& bvh, const Model& model, double scale);

// "" or one warning: a height in the motion outside 0.5-2.5 m while the rest pose's is inside
// (OFFSETs counted twice: about 2x the rest pose's), a mass center lower than 0.35 or higher
// than 0.75 of the height above the lowest joint, or a mass center whose speed differs from the
// pelvis's by more than 25 % over a motion that travels (pelvis > 0.3 m/s): with the likely
// cause (missing segments, named from `missing`; a mapping to check with --segments).
std::string motion_warning(const BvhFile& bvh, const Model& model, double scale,
                           const std::string& missing);

}  // namespace mbk
