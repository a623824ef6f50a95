// ~base_odometry: nav_msgs/Odometry of a floating base into the core's BaseOdometryBuffer
// (doc/node.md "Floating base from odometry"). The first accepted message fixes R (its
// header.frame_id, used as it is); messages in another frame, with NaN/Inf or a zero
// quaternion are refused with the reason. The base is a body of the kinematics model on a free
// joint (core/base_joint.h) whose coordinates come from the odometry at each sample's stamp.
#pragma once

#include <nav_msgs/Odometry.h>

#include <string>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/estimation/base_odometry_buffer.h"

namespace mbk_ros {

class BaseOdometryInput {
 public:
  // `topic`: where the messages come from (resolved), for messages.
  BaseOdometryInput(const mbk::DerivativeEstimator& prototype, double max_gap, std::string topic);

  // The models for `loaded`: `input` has the joints of joint_states, `model` the kinematics. A
  // URDF whose root joint is floating keeps it in `model` (its coordinates from the odometry);
  // any other model gets a base body on a free joint `base_odometry`, named after its root link.
  static void split(const mbk::Model& loaded, mbk::Model& input, mbk::Model& model);

  // Adds a message at time t (seconds); returns why it was refused, else "".
  std::string add(const nav_msgs::Odometry& msg, double t);

  // R: the first accepted message's header.frame_id; "" before it.
  const std::string& frame() const { return frame_; }
  const std::string& topic() const { return topic_; }

  // `state` (of `model`, from split) at time t: the base's coordinates from the odometry
  // (interpolated, or held within the gap, or with `extrapolate` extrapolated: `fit` says
  // which), the joints' from `joints` (of `input`). Lowers `level` to velocities while the
  // base's acceleration is not estimated yet. Returns why there is no base motion for t (and
  // leaves `state` unspecified), else "".
  std::string fill(double t, const mbk::Model& model, const mbk::JointState<double>& joints,
                   mbk::JointState<double>& state, mbk::Level& level, bool extrapolate,
                   mbk::BaseOdometryBuffer::Fit& fit) const;
  // What was done for a sample at t beyond the odometry's ends (held, or extrapolated), and how
  // far beyond, for the diagnostics.
  std::string beyond(double t, bool extrapolated) const;
  // True once odometry at or after t has come (BaseOdometryBuffer::covers).
  bool covers(double t) const { return buffer_.covers(t); }

  void reset();  // forgets the samples and the estimates (R stays)

 private:
  mbk::BaseOdometryBuffer buffer_;
  double max_gap_;
  std::string topic_, frame_;
};

}  // namespace mbk_ros
