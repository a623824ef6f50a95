// A BVH recording (io/bvh.h) as a Model and its frames as the model's coordinates
// (doc/conventions.md#bvh-files). ROS-free.
//
// The skeleton: every ROOT and JOINT is a body named after it, numbered in file order (parents
// first), its OFFSET (times `scale`) the joint origin q_k in the parent's axes, C_k = I, so that
// each body's axes are the BVH joint's axes. The joint follows the segment's CHANNELS:
//   position channels (ROOT or JOINT)  free_123: x, y, z = the position channels (missing ones
//                                      0); the ROOT's are added to its OFFSET, a JOINT's are its
//                                      local translation, in place of the OFFSET along their
//                                      axes (as exporters mean them); the angles as below
//   three rotations                    ball_123 in the channels' order (Zrotation Xrotation
//                                      Yrotation: ZXY, alpha = the Zrotation value, ...)
//   two rotations                      universal for Xrotation Yrotation; any other pair
//                                      ball_123 in that order, completed by the third axis whose
//                                      angle (gamma) stays 0
//   one rotation                       revolute about that axis
//   no channels                        fixed
// Coordinates are named "<joint>/<suffix>" (x y z alpha beta gamma) or, for a revolute joint,
// after the joint. An End Site is no body: it is the segment's tip (bvh_anthropometry.h: how
// tips place the mass centers). With a body mass, the segments' masses, mass centers and
// inertias come from de Leva's table (bvh_anthropometry.h); without, every body is massless.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/bvh.h"

namespace mbk {

// A standing human's height, metres: outside it, a recording's scale is likely wrong.
inline constexpr double kHumanHeight[2] = {0.5, 2.5};

struct BvhModelOptions {
  double scale = 1.0;        // metres per file unit (0.01 for centimetres, 0.0254 for inches)
  double body_mass = 0.0;    // kg; 0 = massless segments
  std::string sex = "male";  // "male" or "female": the anthropometric table's column
  std::string segments{};    // a YAML map joint name -> segment (bvh_segment_map.h); "" none
  std::string anthropometry = "de_leva";  // or "dempster" (bvh_anthropometry.h SegmentTable)
};

// The options from their command-line texts (--scale, --body-mass, --sex, --segments,
// --anthropometry; "" keeps the default). Throws std::invalid_argument naming the option and the
// text (--segments or --anthropometry without --body-mass too).
BvhModelOptions bvh_model_options(const std::string& scale, const std::string& body_mass,
                                  const std::string& sex, const std::string& segments = "",
                                  const std::string& anthropometry = "");

// The model of the file's skeleton. Its warnings (Model::warnings) name what the user should
// know: a standing height outside 0.5-2.5 m (a wrong --scale), bones whose length changes
// during the motion (bvh_bones.h), and with a body mass the segments
// the anthropometric table does not cover. Throws std::invalid_argument "<path>:<line>: ..." for
// channels no joint can take (a repeated rotation axis, more than three rotations) and for a bad
// option.
Model model_from_bvh(const BvhFile& bvh, const BvhModelOptions& options);

// The anthropometric table's segments the skeleton lacks with `options` (bvh_anthropometry.h's
// missing_segments; its --segments map read), e.g. "left hand"; empty without a body mass (no
// whole-body outputs) or when every segment is found.
std::vector<std::string> bvh_missing_segments(const BvhFile& bvh, const BvhModelOptions& options);

// Frame `frame`'s values (from 0) as the coordinates of `model` (made by model_from_bvh from the
// same file), in model.coordinate_names order: radians and metres (positions times `scale`).
std::vector<double> bvh_frame_coordinates(const BvhFile& bvh, const Model& model, int frame,
                                          double scale);

}  // namespace mbk
