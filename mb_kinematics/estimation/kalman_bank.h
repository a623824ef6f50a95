// KalmanEstimator's filters of many coordinates as a structure of arrays: one sample of many
// coordinates at one stamp (a joint_states message) is one vectorized pass over them (AVX2 where
// the CPU has it, without fused multiply-adds), each coordinate's operations in the order of the
// one-filter form, so the estimates are those of separate KalmanEstimators bit for bit.
#pragma once

#include <vector>

#include "mb_kinematics/estimation/estimator_bank.h"

namespace mbk {

class KalmanBank final : public EstimatorBank {
 public:
  // n filters; throws std::invalid_argument unless both settings are finite and > 0.
  KalmanBank(double jerk_density, double position_noise, int n);

  int size() const override { return static_cast<int>(count_.size()); }
  void reset(int i) override { count_[i] = 0; }
  bool add(int i, double t, double x) override;
  int estimate(int i, double& first, double& second) const override;
  // The filters whose sample follows their latest (the common case) in one pass; the others
  // (first sample, repeated stamp, stamps going back, non-finite values) one by one.
  void add(double t, const double* x, const char* use) override;
  using EstimatorBank::bounded;
  bool bounded(const char* use, int derivatives, double bound) const override;
  bool all_estimated(double* first, double* second) const override;

  double jerk_density() const { return q_; }
  double position_noise() const;

 private:
  // Per filter: its latest stamp, its state x, x', x'' and the upper triangle of its symmetric
  // covariance P.
  struct Lanes {
    explicit Lanes(int n);
    std::vector<double> t, s0, s1, s2, p00, p01, p02, p11, p12, p22;
  };
  double q_, r_;
  std::vector<int> count_;  // samples since the last reset (estimates need 3)
  Lanes now_;
  Lanes before_;  // before the latest update: a repeated stamp replaces the latest sample
  std::vector<double> step_;  // add(t, x, use): 1 where the vectorized pass updates the filter
};

}  // namespace mbk
