#include "mb_kinematics/io/bvh_motion_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/bvh_bones.h"
#include "mb_kinematics/io/bvh_model.h"

namespace mbk {
namespace {

constexpr double kMassCenterHeight[2] = {0.35, 0.75};  // of the height, above the lowest joint
constexpr double kSpeedMismatch = 0.25;                // relative
constexpr double kTravelling = 0.3;                    // m/s of the pelvis
constexpr int kMostFrames = 1000;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t middle = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + middle, v.end());
  return v[middle];
}

// Per frame: every body's origin (1..N) and the mass center.
struct Frame {
  std::vector<Vec3<double>> origin;
  Vec3<double> mass_center = Vec3<double>::Zero();
};

// The bodies (1..N) that make the moving skeleton: all but those fixed in space while others
// move (a static ROOT such as Bandai Namco's joint_Root, metres from the walker): with them the
// box around the joints would span the floor between the root and the walker.
std::vector<bool> moving_bodies(const BvhFile& bvh) {
  const std::vector<bool> fixed = fixed_in_space(bvh);
  const bool moves = std::find(fixed.begin(), fixed.end(), false) != fixed.end();
  std::vector<bool> counted(fixed.size() + 1, false);
  for (size_t i = 0; i < fixed.size(); ++i) counted[i + 1] = !moves || !fixed[i];
  return counted;
}

Vec3<double> extent(const std::vector<Vec3<double>>& points, const std::vector<bool>& counted) {
  Vec3<double> low = Vec3<double>::Constant(INFINITY), high = -low;
  for (size_t k = 1; k < points.size(); ++k) {
    if (!counted[k]) continue;
    low = low.cwiseMin(points[k]);
    high = high.cwiseMax(points[k]);
  }
  return high - low;
}

double lowest(const std::vector<Vec3<double>>& points, const std::vector<bool>& counted, int up) {
  double low = INFINITY;
  for (size_t k = 1; k < points.size(); ++k)
    if (counted[k]) low = std::min(low, points[k][up]);
  return low;
}

// The rest pose (every angle 0) as the file means it: a JOINT's position channels are its
// translation in place of its OFFSET (bvh_model.h), so they take the OFFSET's values; the ROOT's,
// added to its OFFSET, stay 0.
std::vector<double> rest_coordinates(const BvhFile& bvh, const Model& model, double scale) {
  std::vector<double> q(model.nq, 0.0);
  for (int k = 1; k <= model.body_count(); ++k) {
    const BvhSegment& segment = bvh.segments[k - 1];
    if (segment.parent < 0) continue;
    for (BvhChannel channel : segment.channels) {
      if (is_rotation(channel)) continue;
      const int axis = static_cast<int>(channel) % 3;  // X, Y, Z position: 0, 1, 2
      q[model.bodies[k].q_index + axis] = scale * segment.offset[axis];
    }
  }
  return q;
}

// Horizontal path length of `point(frame)` over the frames, taken every `step` of them.
template <typename Point>
double path(const std::vector<Frame>& frames, int up, Point point) {
  double length = 0;
  for (size_t f = 1; f < frames.size(); ++f) {
    Vec3<double> d = point(frames[f]) - point(frames[f - 1]);
    d[up] = 0;
    length += d.norm();
  }
  return length;
}

// The first body (in file order) that is not fixed in space: the pelvis of a skeleton whose
// ROOT stays at 0, else the ROOT.
int first_moving(const BvhFile& bvh) {
  const std::vector<bool> fixed = fixed_in_space(bvh);
  for (size_t i = 0; i < fixed.size(); ++i)
    if (!fixed[i]) return static_cast<int>(i) + 1;
  return 1;
}

}  // namespace

MotionFigures motion_figures(const BvhFile& bvh, const Model& model, double scale) {
  MotionFigures m;
  if (bvh.frame_count == 0) return m;
  const int every = std::max(1, static_cast<int>(std::lround(0.1 / bvh.frame_time)));
  const int stride = std::max(every, (bvh.frame_count + kMostFrames - 1) / kMostFrames);
  JointState<double> state(model);
  Data<double> data(model);
  SystemKinematics<double> system;
  std::vector<Frame> frames;
  for (int f = 0; f < bvh.frame_count; f += stride) {
    const std::vector<double> q = bvh_frame_coordinates(bvh, model, f, scale);
    state.position = Eigen::Map<const Eigen::VectorXd>(q.data(), q.size());
    forward_kinematics(model, state, data, Level::kPose);
    system_kinematics(model, data, system, Level::kPose);
    frames.push_back({data.origin, system.mass_center});
  }
  m.has_mass = system.mass > 0;
  const std::vector<bool> counted = moving_bodies(bvh);
  Vec3<double> extents = Vec3<double>::Zero();
  std::vector<double> e[3];
  for (const Frame& f : frames) {
    const Vec3<double> x = extent(f.origin, counted);
    for (int i = 0; i < 3; ++i) e[i].push_back(x[i]);
  }
  for (int i = 0; i < 3; ++i) extents[i] = median(e[i]);
  extents.maxCoeff(&m.up);
  m.height = extents[m.up];
  const std::vector<double> rest = rest_coordinates(bvh, model, scale);
  state.position = Eigen::Map<const Eigen::VectorXd>(rest.data(), rest.size());
  forward_kinematics(model, state, data, Level::kPose);
  m.rest_height = extent(data.origin, counted)[m.up];
  std::vector<double> heights;
  for (const Frame& f : frames)
    heights.push_back(f.mass_center[m.up] - lowest(f.origin, counted, m.up));
  m.mass_center_height = median(heights);
  const double duration = (frames.size() - 1) * stride * bvh.frame_time;
  if (duration <= 0) return m;
  const int root = first_moving(bvh);
  m.mass_center_speed = path(frames, m.up, [](const Frame& f) { return f.mass_center; }) / duration;
  m.root_speed = path(frames, m.up, [&](const Frame& f) { return f.origin[root]; }) / duration;
  return m;
}

std::string motion_warning(const BvhFile& bvh, const Model& model, double scale,
                           const std::string& missing) {
  const MotionFigures m = motion_figures(bvh, model, scale);
  char text[512];
  const auto human = [](double h) { return h >= kHumanHeight[0] && h <= kHumanHeight[1]; };
  if (!human(m.height) && human(m.rest_height)) {
    std::snprintf(text, sizeof text,
                  ": the skeleton is %.3g m tall in its motion (median over the frames) but %.3g "
                  "m at rest: %s",
                  m.height, m.rest_height,
                  std::abs(m.height / m.rest_height - 2) < 0.4
                      ? "about twice, as when OFFSETs are counted twice (a file written by a "
                        "reader that adds a JOINT's position channels to its OFFSET)"
                      : "check the position channels");
    return bvh.path + text;
  }
  if (!m.has_mass || !human(m.height)) return "";
  const double ratio = m.mass_center_height / m.height;
  const bool low = ratio < kMassCenterHeight[0] || ratio > kMassCenterHeight[1];
  const bool slow = m.root_speed > kTravelling &&
                    std::abs(m.mass_center_speed / m.root_speed - 1) > kSpeedMismatch;
  if (!low && !slow) return "";
  std::snprintf(text, sizeof text,
                ": the whole-body mass center is not a human's: %.2f m above the lowest joint "
                "(%.2f of the %.2f m height; 0.35-0.75 expected), moving at %.2f m/s while "
                "the pelvis moves at %.2f m/s: ",
                m.mass_center_height, ratio, m.height, m.mass_center_speed, m.root_speed);
  return bvh.path + text +
         (missing.empty() ? "check the segments' mapping (doc/anthropometry.md, --segments FILE)"
                          : "likely cause: segments not found, " + missing);
}

}  // namespace mbk
