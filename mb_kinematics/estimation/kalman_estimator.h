// A constant-acceleration Kalman filter per coordinate (state x, x', x''; white jerk of
// spectral density `jerk_density`, position noise of standard deviation `position_noise`):
// a tracking filter that handles irregular stamps and noise, with no window latency but a lag
// that grows as jerk_density shrinks.
#pragma once

#include <Eigen/Core>

#include "mb_kinematics/estimation/derivative_estimator.h"

namespace mbk {

class KalmanEstimator : public DerivativeEstimator {
 public:
  // Throws std::invalid_argument unless both are finite and > 0.
  KalmanEstimator(double jerk_density, double position_noise);

  std::unique_ptr<DerivativeEstimator> clone() const override;
  void reset() override { count_ = 0; }
  bool add(double t, double x) override;
  int estimate(double& first, double& second) const override;

 private:
  void predict(double dt);  // the state and covariance dt later, before the measurement

  double q_, r_;
  int count_ = 0;  // samples since the last reset (estimates need 3)
  double t_ = 0;
  Eigen::Vector3d s_;  // x, x', x''
  Eigen::Matrix3d p_;  // covariance
  // Before the latest update, so that a repeated stamp can replace the latest sample.
  double t_before_ = 0;
  Eigen::Vector3d s_before_;
  Eigen::Matrix3d p_before_;
};

}  // namespace mbk
