#include "mb_kinematics/estimation/kalman_estimator.h"

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
  predict(t - t_);
  const double innovation = x - s_[0], variance = p_(0, 0) + r_;
  const Eigen::Vector3d row = p_.col(0), gain = row / variance;  // row 0 of P, as column 0
  s_ += gain * innovation;
  // P <- P - gain P.row(0), on the upper triangle (P symmetric).
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) p_(j, i) = p_(i, j) = p_(i, j) - gain[i] * row[j];
  t_ = t;
  ++count_;
  return forward;
}

// s <- F s, P <- F P F^T + q Q over dt, with F = [1 dt h; 0 1 dt; 0 0 1] (constant
// acceleration, h = dt^2 / 2) and Q the white jerk's discretized covariance. F P F^T multiplied
// out on the upper triangle of the symmetric P: a third of the products of the 3x3 form (the
// node runs one filter per coordinate and sample; doc/speed.md "The node's load").
void KalmanEstimator::predict(double dt) {
  const double d2 = dt * dt, h = d2 / 2, d3 = d2 * dt;
  s_[0] += dt * s_[1] + h * s_[2];
  s_[1] += dt * s_[2];
  Eigen::Matrix3d& p = p_;
  // Rows of A = F P: a0j = p0j + dt p1j + h p2j, a1j = p1j + dt p2j (j >= row), a2j = p2j.
  const double a00 = p(0, 0) + dt * p(1, 0) + h * p(2, 0);
  const double a01 = p(0, 1) + dt * p(1, 1) + h * p(2, 1);
  const double a02 = p(0, 2) + dt * p(1, 2) + h * p(2, 2);
  const double a11 = p(1, 1) + dt * p(2, 1), a12 = p(1, 2) + dt * p(2, 2);
  // (A F^T)ij = ai0 + dt ai1 + h ai2, ai1 + dt ai2, ai2 for j = 0, 1, 2.
  p(0, 0) = a00 + dt * a01 + h * a02 + q_ * (d3 * d2 / 20);
  p(0, 1) = p(1, 0) = a01 + dt * a02 + q_ * (d2 * d2 / 8);
  p(0, 2) = p(2, 0) = a02 + q_ * (d3 / 6);
  p(1, 1) = a11 + dt * a12 + q_ * (d3 / 3);
  p(1, 2) = p(2, 1) = a12 + q_ * (d2 / 2);
  p(2, 2) += q_ * dt;
}

int KalmanEstimator::estimate(double& first, double& second) const {
  if (count_ < 3) return 0;
  first = s_[1];
  second = s_[2];
  return 2;
}

}  // namespace mbk
