// The node's online buffer of a floating base's odometry (doc/node.md "Floating base from
// odometry"): the newest BaseSamples (core/floating_base.h) with the base's acceleration from an
// online DerivativeEstimator on the velocities in R, read at a joint sample's stamp by
// interpolate_base (pose by slerp, twist linearly) or, within a gap beyond the first or last
// sample, held or extrapolated. mbk bag reads the same BaseSample/BaseMotion offline. ROS-free
// (Eigen only).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/estimation/derivative_estimator.h"

namespace mbk {

// Why a BaseSample was refused (NaN/Inf, an orientation of near-zero norm); empty if accepted.
std::string check_base_sample(const BaseSample& s);

class BaseOdometryBuffer {
 public:
  // `prototype`: the estimator of the acceleration (the first derivative of each R component
  // of the velocity and angular velocity). `max_gap` (s): how far beyond the first or last
  // sample a stamp may be and still take that sample's motion (held), and the longest pause
  // interpolated or differentiated across.
  BaseOdometryBuffer(const DerivativeEstimator& prototype, double max_gap);

  // Adds a sample; returns why it was refused (check_base_sample), else "". A stamp before the
  // newest one (a bag looping) or more than max_gap after it (a pause) restarts the buffer and
  // the estimators; the same stamp again replaces the newest sample.
  std::string add(const BaseSample& s);
  void reset();

  enum class Fit { kEmpty, kInterpolated, kHeld, kExtrapolated, kTooOld, kTooNew };
  // The motion at time t: between two samples interpolated (interpolate_base); within max_gap
  // of the first or last sample, that sample's (held), or with `extrapolate` that sample's twist
  // carried on to t (extrapolate_base); farther, kTooOld (t before the first sample) or kTooNew
  // (after the last), and `out` is unchanged. `has_acceleration` is false while the estimator
  // has too few samples for the samples used (accelerations then zero).
  Fit at(double t, BaseMotion& out, bool& has_acceleration, bool extrapolate = false) const;

  // True once a sample at or after t has come: at(t) interpolates, no later sample changes it.
  bool covers(double t) const { return !samples_.empty() && last_stamp() >= t; }

  double first_stamp() const { return samples_.empty() ? 0 : samples_.front().t; }
  double last_stamp() const { return samples_.empty() ? 0 : samples_.back().t; }

 private:
  void trim();

  std::unique_ptr<DerivativeEstimator> estimators_[6];  // velocity x y z, omega x y z, in R
  double max_gap_;
  std::vector<BaseSample> samples_;  // the newest few, oldest first (orientations normalized)
  std::vector<Vec3<double>> linear_acceleration_, angular_acceleration_;  // per sample, in R
  std::vector<char> valid_;  // per sample: the estimator gave its acceleration
};

}  // namespace mbk
