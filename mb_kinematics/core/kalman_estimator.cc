#include "mb_kinematics/core/kalman_estimator.h"

#include <cmath>
#include <stdexcept>

namespace mbk {

KalmanEstimator::KalmanEstimator(double jerk_density, double position_noise)
    : q_(jerk_density), r_(position_noise * position_noise) {
  if (!(std::isfinite(jerk_density) && jerk_density > 0 && std::isfinite(position_noise) &&
        position_noise > 0))
    throw std::invalid_argument("kalman: jerk density and position noise must be finite and > 0");
}

std::unique_ptr<DerivativeEstimator> KalmanEstimator::clone() const {
  return std::make_unique<KalmanEstimator>(q_, std::sqrt(r_));
}

bool KalmanEstimator::add(double t, double x) {
  if (!std::isfinite(t) || !std::isfinite(x)) return false;
  if (count_ > 0 && t == t_) {  // a repeated stamp replaces the sample (derivative_estimator.h)
    if (count_ == 1) {
      s_[0] = x;
      return true;
    }
    s_ = s_before_, p_ = p_before_, t_ = t_before_;  // undo the last update, redo it with x
    --count_;
  }
  const bool forward = count_ == 0 || t > t_;
  if (!forward) reset();  // stamps went back (a bag looping): start over
  if (count_ == 0) {
    s_ << x, 0, 0;
    p_ = Eigen::Vector3d(r_, 1e6, 1e12).asDiagonal();  // position known, the rest not
    t_ = t;
    count_ = 1;
    return forward;
  }
  s_before_ = s_, p_before_ = p_, t_before_ = t_;
  const double dt = t - t_;
  Eigen::Matrix3d f;  // constant acceleration over dt
  f << 1, dt, dt * dt / 2, 0, 1, dt, 0, 0, 1;
  Eigen::Matrix3d q;  // white jerk (discretized)
  const double d2 = dt * dt, d3 = d2 * dt;
  q << d3 * d2 / 20, d2 * d2 / 8, d3 / 6, d2 * d2 / 8, d3 / 3, d2 / 2, d3 / 6, d2 / 2, dt;
  s_ = f * s_;
  p_ = f * p_ * f.transpose() + q_ * q;
  const double innovation = x - s_[0], variance = p_(0, 0) + r_;
  const Eigen::Vector3d gain = p_.col(0) / variance;
  s_ += gain * innovation;
  p_ -= gain * p_.row(0);
  t_ = t;
  ++count_;
  return forward;
}

int KalmanEstimator::estimate(double& first, double& second) const {
  if (count_ < 3) return 0;
  first = s_[1];
  second = s_[2];
  return 2;
}

}  // namespace mbk
