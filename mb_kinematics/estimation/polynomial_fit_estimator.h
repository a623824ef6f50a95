// Derivatives from a least-squares polynomial through the last `window` samples (non-uniform
// times allowed), evaluated `latency` samples back from the newest: Savitzky-Golay filtering
// generalized to irregular stamps. window 3, order 2 is the 3-point difference: latency 0 the
// backward difference, latency 1 the central difference.
#pragma once

#include <Eigen/Core>

#include "mb_kinematics/estimation/derivative_estimator.h"

namespace mbk {

class PolynomialFitEstimator : public DerivativeEstimator {
 public:
  static constexpr int kMaxWindow = 31;
  static constexpr int kMaxOrder = 5;

  // Throws std::invalid_argument unless 2 <= order + 1 <= window <= kMaxWindow, order <=
  // kMaxOrder and 0 <= latency < window.
  PolynomialFitEstimator(int window, int order, int latency);

  std::unique_ptr<DerivativeEstimator> clone() const override;
  void reset() override { count_ = 0; }
  bool add(double t, double x) override;
  int estimate(double& first, double& second) const override;
  int latency() const override { return latency_; }

 private:
  int window_, order_, latency_;
  int count_ = 0;  // samples held, newest at t_[count_ - 1]
  double t_[kMaxWindow], x_[kMaxWindow];
};

}  // namespace mbk
