#include "mb_kinematics/ros/base_odometry_input.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

#include "mb_kinematics/core/base_joint.h"
#include "mb_kinematics/core/quaternion_scale.h"

namespace mbk_ros {

BaseOdometryInput::BaseOdometryInput(const mbk::DerivativeEstimator& prototype, double max_gap,
                                     std::string topic)
    : buffer_(prototype, max_gap), max_gap_(max_gap), topic_(std::move(topic)) {}

void BaseOdometryInput::split(const mbk::Model& loaded, mbk::Model& input, mbk::Model& model) {
  if (mbk::has_floating_root(loaded)) {
    input = mbk::without_root_body(loaded);
    model = loaded;
  } else {
    input = loaded;
    model = mbk::with_floating_base(loaded, "odometry", "base_odometry");  // R: frame()
  }
}

std::string BaseOdometryInput::add(const nav_msgs::Odometry& msg, double t) {
  if (msg.header.frame_id.empty()) return "odometry without header.frame_id";
  if (!frame_.empty() && msg.header.frame_id != frame_)
    return "odometry frame_id '" + msg.header.frame_id + "' differs from R = '" + frame_ +
           "' (the first message's)";
  mbk::BaseSample s;
  s.t = t;
  const auto& p = msg.pose.pose;
  s.position = mbk::Vec3<double>(p.position.x, p.position.y, p.position.z);
  s.orientation =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  mbk::scale_large_quaternion(s.orientation);  // components of 1e154 and more: a finite norm
  const auto& v = msg.twist.twist;             // in child_frame_id, the base's frame (nav_msgs)
  s.linear = mbk::Vec3<double>(v.linear.x, v.linear.y, v.linear.z);
  s.angular = mbk::Vec3<double>(v.angular.x, v.angular.y, v.angular.z);
  const std::string error = buffer_.add(s);
  if (error.empty() && frame_.empty()) frame_ = msg.header.frame_id;
  return error;
}

std::string BaseOdometryInput::fill(double t, const mbk::Model& model,
                                    const mbk::JointState<double>& joints,
                                    mbk::JointState<double>& state, mbk::Level& level,
                                    bool extrapolate, mbk::BaseOdometryBuffer::Fit& fit) const {
  using Fit = mbk::BaseOdometryBuffer::Fit;
  mbk::BaseMotion m;
  bool has_acceleration = false;
  fit = buffer_.at(t, m, has_acceleration, extrapolate);
  if (fit == Fit::kEmpty) return "no base odometry yet";
  if (fit == Fit::kTooOld || fit == Fit::kTooNew) {
    const bool old = fit == Fit::kTooOld;
    std::ostringstream why;
    why << std::fixed << std::setprecision(3) << "base odometry " << (old ? "starts " : "ends ")
        << std::abs(t - (old ? buffer_.first_stamp() : buffer_.last_stamp())) << " s "
        << (old ? "after" : "before") << " the sample, beyond ~base_odometry_max_gap (" << max_gap_
        << " s)";
    return why.str();
  }
  const long n = joints.position.size();
  state.position.tail(n) = joints.position;
  state.velocity.tail(n) = joints.velocity;
  state.acceleration.tail(n) = joints.acceleration;
  if (!has_acceleration) level = std::min(level, mbk::Level::kVelocity);
  return mbk::free_joint_coordinates(model.bodies[1].joint, m, state.position.data(),
                                     state.velocity.data(),
                                     has_acceleration ? state.acceleration.data() : nullptr);
}

std::string BaseOdometryInput::beyond(double t, bool extrapolated) const {
  const bool before = t < buffer_.first_stamp();
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << "base odometry "
      << (extrapolated ? "extrapolated" : "held") << " for the sample at " << t
      << " s: the odometry " << (before ? "starts " : "ends ")
      << std::abs(t - (before ? buffer_.first_stamp() : buffer_.last_stamp())) << " s "
      << (before ? "after" : "before") << " it, none "
      << (before ? "earlier" : "later within ~base_odometry_wait");
  return out.str();
}

void BaseOdometryInput::reset() { buffer_.reset(); }

}  // namespace mbk_ros
