// The derivative estimators of many coordinates side by side (DerivativeEstimator::bank): each
// one as its own estimator (the same calls, by index), and one sample of many of them taken in
// one call, which an estimator kind may do in a vectorized pass (KalmanBank).
#pragma once

#include <memory>
#include <vector>

#include "mb_kinematics/estimation/derivative_estimator.h"

namespace mbk {

class EstimatorBank {
 public:
  virtual ~EstimatorBank() = default;
  virtual int size() const = 0;
  // Estimator i's DerivativeEstimator::reset, add and estimate.
  virtual void reset(int i) = 0;
  virtual bool add(int i, double t, double x) = 0;
  virtual int estimate(int i, double& first, double& second) const = 0;
  // x[i] at t added to each estimator i with use[i] != 0 (arrays of size()), as add(i, t, x[i]).
  virtual void add(double t, const double* x, const char* use);
  // True if the first `derivatives` (1 or 2) estimates that estimate(i) gives are within
  // `bound` in magnitude (NaN is not).
  bool bounded(int i, int derivatives, double bound) const;
  // bounded(i, derivatives, bound) for each i with use[i] != 0.
  virtual bool bounded(const char* use, int derivatives, double bound) const;
  // True if every estimator gives both derivatives (estimate(i) returns 2): then first[i] and
  // second[i] (when `second` is not null) are estimator i's; else the arrays are left as they
  // are.
  virtual bool all_estimated(double* first, double* second) const;
};

// Clones of one estimator, one per index: the bank of any kind.
class ClonedBank : public EstimatorBank {
 public:
  ClonedBank(const DerivativeEstimator& prototype, int n);
  int size() const override { return static_cast<int>(estimators_.size()); }
  void reset(int i) override { estimators_[i]->reset(); }
  bool add(int i, double t, double x) override { return estimators_[i]->add(t, x); }
  int estimate(int i, double& first, double& second) const override {
    return estimators_[i]->estimate(first, second);
  }
  using EstimatorBank::add;

 private:
  std::vector<std::unique_ptr<DerivativeEstimator>> estimators_;
};

}  // namespace mbk
