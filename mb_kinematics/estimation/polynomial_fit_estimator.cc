#include "mb_kinematics/estimation/polynomial_fit_estimator.h"

#include <Eigen/QR>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mbk {

PolynomialFitEstimator::PolynomialFitEstimator(int window, int order, int latency)
    : window_(window), order_(order), latency_(latency) {
  if (order < 1 || order > kMaxOrder || window < order + 1 || window > kMaxWindow || latency < 0 ||
      latency >= window)
    throw std::invalid_argument("polynomial fit: need 1 <= order <= " + std::to_string(kMaxOrder) +
                                ", order < window <= " + std::to_string(kMaxWindow) +
                                ", 0 <= latency < window (got window " + std::to_string(window) +
                                ", order " + std::to_string(order) + ", latency " +
                                std::to_string(latency) + ")");
}

std::unique_ptr<DerivativeEstimator> PolynomialFitEstimator::clone() const {
  return std::make_unique<PolynomialFitEstimator>(window_, order_, latency_);
}

bool PolynomialFitEstimator::add(double t, double x) {
  if (!std::isfinite(t) || !std::isfinite(x)) return false;
  if (count_ > 0 && t == t_[count_ - 1]) {  // a repeated stamp replaces the sample
    x_[count_ - 1] = x;
    return true;
  }
  const bool forward = count_ == 0 || t > t_[count_ - 1];
  if (!forward) reset();  // stamps went back (a bag looping): start over
  if (count_ == window_) {
    for (int i = 1; i < window_; ++i) t_[i - 1] = t_[i], x_[i - 1] = x_[i];
    --count_;
  }
  t_[count_] = t;
  x_[count_] = x;
  ++count_;
  return forward;
}

int PolynomialFitEstimator::estimate(double& first, double& second) const {
  if (count_ < window_) return 0;
  using Matrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxWindow, kMaxOrder + 1>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxWindow, 1>;
  const double t0 = t_[count_ - 1 - latency_];
  const double scale = t_[count_ - 1] - t_[0];  // well-conditioned powers of (t - t0) / scale
  Matrix a(count_, order_ + 1);
  Vector b(count_);
  for (int i = 0; i < count_; ++i) {
    const double s = (t_[i] - t0) / scale;
    double p = 1;
    for (int j = 0; j <= order_; ++j, p *= s) a(i, j) = p;
    b[i] = x_[i];
  }
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxOrder + 1, 1> c =
      a.colPivHouseholderQr().solve(b);
  first = c[1] / scale;
  second = order_ >= 2 ? 2 * c[2] / (scale * scale) : 0.0;
  return order_ >= 2 ? 2 : 1;
}

}  // namespace mbk
