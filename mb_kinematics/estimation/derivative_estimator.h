// Time derivatives of one coordinate from its successive samples (t, x), for joint states
// that come without velocities or accelerations (doc/method.md 8). Several
// estimators share this interface; the node picks one by name (~acceleration_estimator).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace mbk {

class EstimatorBank;

class DerivativeEstimator {
 public:
  virtual ~DerivativeEstimator() = default;
  // A new estimator of the same kind and settings, with an empty history.
  virtual std::unique_ptr<DerivativeEstimator> clone() const = 0;
  // Forgets every sample.
  virtual void reset() = 0;
  // Adds x at time t (seconds). A t before the latest sample's (a bag looping) resets the
  // history first and returns false; a t equal to it replaces that sample. A non-finite t or x
  // is not added (returns false).
  virtual bool add(double t, double x) = 0;
  // The first and second derivative at the latest sample's time. Returns how many are valid:
  // 0 (too few samples), 1 (first only) or 2.
  virtual int estimate(double& first, double& second) const = 0;
  // How many samples before the newest the estimates refer to (0: at the newest sample).
  virtual int latency() const { return 0; }
  // n estimators of this kind and settings, each with an empty history (estimator_bank.h).
  virtual std::unique_ptr<EstimatorBank> bank(int n) const;
};

// Estimators by name (derivative_estimator_names() lists the studied ones; doc/error_vs_runtime.md
// compares them; the node's default is "kalman_smooth", doc/node.md).
// "backward_difference": the derivatives at the newest sample of the quadratic through
// the last three samples (non-uniform 3-point backward difference; exact for quadratics, first
// derivative O(h^2), second O(h)); with two samples, the first derivative of the line through
// them. Throws std::invalid_argument naming the known estimators.
std::unique_ptr<DerivativeEstimator> make_derivative_estimator(const std::string& name);
const std::vector<std::string>& derivative_estimator_names();

}  // namespace mbk
