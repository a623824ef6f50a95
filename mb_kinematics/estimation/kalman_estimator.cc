#include "mb_kinematics/estimation/kalman_estimator.h"

namespace mbk {

KalmanEstimator::KalmanEstimator(double jerk_density, double position_noise)
    : filter_(jerk_density, position_noise, 1) {}

std::unique_ptr<DerivativeEstimator> KalmanEstimator::clone() const {
  return std::make_unique<KalmanEstimator>(filter_.jerk_density(), filter_.position_noise());
}

std::unique_ptr<EstimatorBank> KalmanEstimator::bank(int n) const {
  return std::make_unique<KalmanBank>(filter_.jerk_density(), filter_.position_noise(), n);
}

}  // namespace mbk
