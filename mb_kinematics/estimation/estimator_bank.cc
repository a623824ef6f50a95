#include "mb_kinematics/estimation/estimator_bank.h"

#include <algorithm>
#include <cmath>

namespace mbk {

void EstimatorBank::add(double t, const double* x, const char* use) {
  for (int i = 0; i < size(); ++i)
    if (use[i]) add(i, t, x[i]);
}

bool EstimatorBank::bounded(int i, int derivatives, double bound) const {
  double d[2] = {0, 0};
  const int n = std::min(estimate(i, d[0], d[1]), derivatives);
  for (int k = 0; k < n; ++k)
    if (!(std::abs(d[k]) <= bound)) return false;  // NaN too
  return true;
}

bool EstimatorBank::bounded(const char* use, int derivatives, double bound) const {
  for (int i = 0; i < size(); ++i)
    if (use[i] && !bounded(i, derivatives, bound)) return false;
  return true;
}

bool EstimatorBank::all_estimated(double* first, double* second) const {
  double d[2];
  for (int i = 0; i < size(); ++i)
    if (estimate(i, d[0], d[1]) < 2) return false;
  for (int i = 0; i < size(); ++i) {
    estimate(i, first[i], d[1]);
    if (second) second[i] = d[1];
  }
  return true;
}

ClonedBank::ClonedBank(const DerivativeEstimator& prototype, int n) {
  estimators_.reserve(n);
  for (int i = 0; i < n; ++i) estimators_.push_back(prototype.clone());
}

std::unique_ptr<EstimatorBank> DerivativeEstimator::bank(int n) const {
  return std::make_unique<ClonedBank>(*this, n);
}

}  // namespace mbk
