#include "mb_kinematics/io/bvh_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/bvh_anthropometry.h"
#include "mb_kinematics/io/bvh_bones.h"
#include "mb_kinematics/io/bvh_motion_check.h"
#include "mb_kinematics/io/name_list.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {
namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail(const BvhFile& bvh, const BvhSegment& segment, const std::string& what) {
  throw std::invalid_argument(printable(bvh.path + ":" + std::to_string(segment.line) + ": " +
                                        (segment.parent < 0 ? "ROOT " : "JOINT ") + segment.name +
                                        ": " + what));
}

int axis_of(BvhChannel channel) { return static_cast<int>(channel) % 3; }  // X, Y, Z -> 0, 1, 2

// The segment's rotation axes in channel order; whether it has position channels.
struct Channels {
  std::vector<int> rotations;
  bool positions = false;
  std::array<bool, 3> position_axes{};  // X, Y, Z: whether a position channel gives it
};

Channels channels_of(const BvhFile& bvh, const BvhSegment& segment) {
  Channels c;
  std::array<bool, 3>& seen = c.position_axes;
  for (BvhChannel channel : segment.channels) {
    const int axis = axis_of(channel);
    if (is_rotation(channel)) {
      if (!c.rotations.empty() && c.rotations.back() == axis)
        fail(bvh, segment, "two successive rotations about one axis");
      c.rotations.push_back(axis);
    } else {
      if (seen[axis]) fail(bvh, segment, "two position channels along one axis");
      seen[axis] = c.positions = true;
    }
  }
  if (c.rotations.size() > 3) fail(bvh, segment, "more than three rotation channels");
  return c;
}

// The channels' rotation axes completed to three (the added angles stay 0): the order of a
// ball_123 or free_123 joint.
EulerOrder completed_order(std::vector<int> axes) {
  if (axes.empty()) axes.push_back(0);
  if (axes.size() == 1) axes.push_back((axes[0] + 1) % 3);
  if (axes.size() == 2) axes.push_back(3 - axes[0] - axes[1]);
  return euler_order_from_axes({axes[0], axes[1], axes[2]});
}

Joint joint_of(const BvhFile& bvh, const BvhSegment& segment, double scale) {
  const Channels c = channels_of(bvh, segment);
  Joint joint;
  joint.name = segment.name;
  joint.offset = scale * segment.offset;
  // A JOINT's position channels are its whole local translation (doc/conventions.md#bvh-files):
  // they replace the OFFSET along their axes. The ROOT's are added to its OFFSET.
  if (segment.parent >= 0)
    for (int axis = 0; axis < 3; ++axis)
      if (c.position_axes[axis]) joint.offset[axis] = 0;
  const size_t n = c.rotations.size();
  if (c.positions) {
    joint.type = JointType::kFree123;
  } else if (n == 3 || (n == 2 && !(c.rotations[0] == 0 && c.rotations[1] == 1))) {
    joint.type = JointType::kBall123;
  } else if (n == 2) {
    joint.type = JointType::kUniversal;
  } else if (n == 1) {
    joint.type = JointType::kRevolute;
    joint.axis = Vec3<double>::Unit(c.rotations[0]);
  }
  if (takes_euler_order(joint.type)) joint.euler_order = completed_order(c.rotations);
  return joint;
}

// The largest side of the box around the rest pose's joints and End Sites (all angles 0), in
// metres: the standing height of a skeleton standing or in a T-pose.
double rest_extent(const BvhFile& bvh, double scale) {
  // A ROOT fixed in space while the body moves (Bandai Namco's joint_Root, 4.5 m from the pelvis
  // at rest) is no part of the body's height.
  const std::vector<bool> fixed = fixed_in_space(bvh);
  const bool moves = std::find(fixed.begin(), fixed.end(), false) != fixed.end();
  std::vector<Vec3<double>> origin(bvh.segments.size());
  Vec3<double> low = Vec3<double>::Constant(INFINITY), high = -low;
  for (size_t i = 0; i < bvh.segments.size(); ++i) {
    const BvhSegment& s = bvh.segments[i];
    origin[i] = scale * s.offset + (s.parent < 0 ? Vec3<double>::Zero() : origin[s.parent]);
    if (moves && fixed[i]) continue;
    low = low.cwiseMin(origin[i]);
    high = high.cwiseMax(origin[i]);
    if (!s.has_end_site) continue;
    low = low.cwiseMin(origin[i] + scale * s.end_site);
    high = high.cwiseMax(origin[i] + scale * s.end_site);
  }
  return (high - low).maxCoeff();
}

// A name used twice would make two bodies, tf frames and coordinate sets of one name.
void refuse_repeated_names(const BvhFile& bvh) {
  std::unordered_map<std::string, int> first;  // name -> segment
  for (size_t i = 0; i < bvh.segments.size(); ++i) {
    const auto [it, fresh] = first.emplace(bvh.segments[i].name, static_cast<int>(i));
    if (!fresh)
      fail(bvh, bvh.segments[i],
           "a second segment of this name (the first at line " +
               std::to_string(bvh.segments[it->second].line) + ")");
  }
}

// A scale --scale and model_from_bvh accept: metres per file unit, positive and finite.
bool is_scale(double scale) { return scale > 0 && std::isfinite(scale); }

// The file unit that makes a skeleton `extent` file units tall most human: of the common units
// whose height falls in the human range, the one nearest 1.7 m (by ratio); without one, the
// scale that makes it 1.7 m. Returns the scale and a name for it ("" for a computed one).
std::pair<double, std::string> human_scale(double extent) {
  constexpr double kTypicalHeight = 1.7;  // metres
  const std::pair<double, const char*> units[] = {{1.0, "metres"},
                                                  {0.01, "centimetres"},
                                                  {0.001, "millimetres"},
                                                  {0.0254, "inches"},
                                                  {0.0254 / 0.45, "CMU's 1/0.45 inch"}};
  std::pair<double, std::string> best{kTypicalHeight / extent, ""};
  double best_ratio = INFINITY;
  for (const auto& [scale, name] : units) {
    const double height = scale * extent;
    const double ratio = std::abs(std::log(height / kTypicalHeight));
    if (height >= kHumanHeight[0] && height <= kHumanHeight[1] && ratio < best_ratio)
      best = {scale, name}, best_ratio = ratio;
  }
  return best;
}

std::string height_warning(const BvhFile& bvh, double scale) {
  const double height = rest_extent(bvh, scale);
  if (height >= kHumanHeight[0] && height <= kHumanHeight[1]) return "";
  std::ostringstream s;
  s << bvh.path << ": the skeleton's standing height is " << height
    << " m (the rest pose's largest extent, file units times the scale " << scale
    << "), outside a human's " << kHumanHeight[0] << "-" << kHumanHeight[1] << " m";
  if (!(height > 0)) return s.str() + ": the rest pose has no extent";
  const auto [human, unit] = human_scale(height / scale);
  if (!is_scale(human))
    return s.str() + ": its " + format_double(height / scale) + " file units are too " +
           (human > 1 ? "small" : "large") + " for any --scale to make it human";
  s << ": --scale " << std::setprecision(5) << human << " (bvh.launch scale:=" << human
    << ", the node's ~scale) gives " << std::setprecision(3) << human * height / scale << " m"
    << (unit.empty() ? "" : " (file units in " + unit + ")");
  return s.str();
}

SegmentMap segment_map(const BvhModelOptions& options) {
  return options.segments.empty() ? SegmentMap{} : read_segment_map(options.segments);
}

double number(const std::string& option, const std::string& text, double fallback) {
  if (text.empty()) return fallback;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(x))
    throw std::invalid_argument(option + " needs a number, not '" + text + "'");
  return x;
}

}  // namespace

BvhModelOptions bvh_model_options(const std::string& scale, const std::string& body_mass,
                                  const std::string& sex, const std::string& segments,
                                  const std::string& anthropometry) {
  BvhModelOptions o;
  if (!anthropometry.empty()) o.anthropometry = anthropometry;
  o.segments = segments;
  o.scale = number("--scale", scale, o.scale);
  o.body_mass = number("--body-mass", body_mass, o.body_mass);
  if (!sex.empty()) o.sex = sex;
  if (!is_scale(o.scale)) throw std::invalid_argument("--scale needs metres per file unit > 0");
  if (!(o.body_mass >= 0)) throw std::invalid_argument("--body-mass needs kg >= 0");
  if (!segments.empty() && o.body_mass == 0)
    throw std::invalid_argument("--segments maps joints to masses: it needs --body-mass KG");
  if (!anthropometry.empty() && o.body_mass == 0)
    throw std::invalid_argument(
        "--anthropometry chooses the masses' table: it needs --body-mass KG");
  sex_from_string(o.sex);
  segment_table_from_string(o.anthropometry);
  return o;
}

Model model_from_bvh(const BvhFile& bvh, const BvhModelOptions& options) {
  if (!is_scale(options.scale))
    throw std::invalid_argument("scale: must be a positive number of metres per file unit");
  if (!(options.body_mass >= 0) || !std::isfinite(options.body_mass))
    throw std::invalid_argument("body mass: must be a number of kg >= 0 (0: massless segments)");
  const Sex sex = sex_from_string(options.sex);
  const SegmentTable table = segment_table_from_string(options.anthropometry);
  refuse_repeated_names(bvh);
  Model model;
  model.bodies.resize(bvh.segments.size() + 1);
  for (size_t i = 0; i < bvh.segments.size(); ++i) {
    const BvhSegment& segment = bvh.segments[i];
    Body& body = model.bodies[i + 1];
    body.name = segment.name;
    body.lower = segment.parent + 1;
    body.joint = joint_of(bvh, segment, options.scale);
  }
  std::vector<std::string> warnings = {height_warning(bvh, options.scale),
                                       changing_bones_warning(bvh, options.scale)};
  if (options.body_mass > 0)
    for (const std::string& note : set_segment_parameters(bvh, options.scale, options.body_mass,
                                                          sex, model, segment_map(options), table))
      warnings.push_back(note);
  finalize_model(model);
  warnings.push_back(
      motion_warning(bvh, model, options.scale, name_list(bvh_missing_segments(bvh, options))));
  for (const std::string& warning : warnings)
    if (!warning.empty()) model.warnings.push_back(warning);
  return model;
}

std::vector<std::string> bvh_missing_segments(const BvhFile& bvh, const BvhModelOptions& options) {
  if (!(options.body_mass > 0)) return {};
  return missing_segments(bvh, options.scale, segment_map(options));
}

std::vector<double> bvh_frame_coordinates(const BvhFile& bvh, const Model& model, int frame,
                                          double scale) {
  if (frame < 0 || frame >= bvh.frame_count)
    throw std::invalid_argument(bvh.path + ": frame " + std::to_string(frame) +
                                " does not exist (the file has frames 0 to " +
                                std::to_string(bvh.frame_count - 1) + ")");
  if (model.body_count() != static_cast<int>(bvh.segments.size()))
    throw std::invalid_argument(bvh.path + ": the model is not this file's skeleton");
  std::vector<double> q(model.nq, 0.0);
  for (int k = 1; k <= model.body_count(); ++k) {
    const BvhSegment& segment = bvh.segments[k - 1];
    const Body& body = model.bodies[k];
    if (body.name != segment.name)
      throw std::invalid_argument(printable(bvh.path + ": body " + std::to_string(k) + " is " +
                                            body.name + ", not the file's " + segment.name));
    const int translations = translation_count(body.joint.type);
    int angle = 0;
    for (size_t i = 0; i < segment.channels.size(); ++i) {
      const BvhChannel channel = segment.channels[i];
      const double value = bvh.value(frame, segment.first_column + static_cast<int>(i));
      if (is_rotation(channel))
        q[body.q_index + translations + angle++] = value * kPi / 180.0;
      else
        q[body.q_index + axis_of(channel)] = value * scale;
    }
  }
  return q;
}

}  // namespace mbk
