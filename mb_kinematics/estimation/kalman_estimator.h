// A constant-acceleration Kalman filter per coordinate (state x, x', x''; white jerk of
// spectral density `jerk_density`, position noise of standard deviation `position_noise`):
// a tracking filter that handles irregular stamps and noise, with no window latency but a lag
// that grows as jerk_density shrinks. The filter is a KalmanBank of one (kalman_bank.h).
#pragma once

#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/estimation/kalman_bank.h"

namespace mbk {

class KalmanEstimator : public DerivativeEstimator {
 public:
  // Throws std::invalid_argument unless both are finite and > 0.
  KalmanEstimator(double jerk_density, double position_noise);

  std::unique_ptr<DerivativeEstimator> clone() const override;
  void reset() override { filter_.reset(0); }
  bool add(double t, double x) override { return filter_.add(0, t, x); }
  int estimate(double& first, double& second) const override {
    return filter_.estimate(0, first, second);
  }
  // A KalmanBank: a sample of many coordinates in one vectorized pass.
  std::unique_ptr<EstimatorBank> bank(int n) const override;

 private:
  KalmanBank filter_;
};

}  // namespace mbk
