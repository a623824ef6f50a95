#include "mb_kinematics/estimation/derivative_estimator.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mb_kinematics/estimation/kalman_estimator.h"
#include "mb_kinematics/estimation/polynomial_fit_estimator.h"

namespace mbk {
namespace {

// Keeps the last three samples; t[2] is the newest.
class BackwardDifference : public DerivativeEstimator {
 public:
  std::unique_ptr<DerivativeEstimator> clone() const override {
    return std::make_unique<BackwardDifference>();
  }

  void reset() override { count_ = 0; }

  bool add(double t, double x) override {
    if (!std::isfinite(t) || !std::isfinite(x)) return false;
    if (count_ > 0 && t == t_[2]) {
      x_[2] = x;
      return true;
    }
    const bool forward = count_ == 0 || t > t_[2];
    if (!forward) reset();
    for (int i = 0; i < 2; ++i) {
      t_[i] = t_[i + 1];
      x_[i] = x_[i + 1];
    }
    t_[2] = t;
    x_[2] = x;
    if (count_ < 3) ++count_;
    return forward;
  }

  int estimate(double& first, double& second) const override {
    if (count_ < 2) return 0;
    const double h2 = t_[2] - t_[1];
    if (count_ == 2) {
      first = (x_[2] - x_[1]) / h2;
      return 1;
    }
    const double h1 = t_[1] - t_[0], h = h1 + h2;
    first = x_[0] * h2 / (h1 * h) - x_[1] * h / (h1 * h2) + x_[2] * (h1 + 2 * h2) / (h2 * h);
    second = 2 * (x_[0] / (h1 * h) - x_[1] / (h1 * h2) + x_[2] / (h2 * h));
    return 2;
  }

 private:
  double t_[3] = {0, 0, 0}, x_[3] = {0, 0, 0};
  int count_ = 0;
};

// savitzky_golay_<window>_<order>: evaluated at the window's center (latency (window-1)/2);
// savitzky_golay_end_<window>_<order>: at its newest sample (no latency). nullptr for another
// name.
std::unique_ptr<DerivativeEstimator> savitzky_golay(const std::string& name) {
  int window = 0, order = 0, used = 0;
  const bool end =
      std::sscanf(name.c_str(), "savitzky_golay_end_%d_%d%n", &window, &order, &used) == 2;
  if ((end || std::sscanf(name.c_str(), "savitzky_golay_%d_%d%n", &window, &order, &used) == 2) &&
      used == static_cast<int>(name.size()))
    return std::make_unique<PolynomialFitEstimator>(window, order, end ? 0 : (window - 1) / 2);
  return nullptr;
}

template <typename E, typename... Args>
std::unique_ptr<DerivativeEstimator> make(Args... args) {
  return std::make_unique<E>(args...);
}

// The studied estimators, in the order of derivative_estimator_names(): each name with its
// estimator's maker (nullptr: a Savitzky-Golay fit made from the name itself).
struct Named {
  const char* name;
  std::unique_ptr<DerivativeEstimator> (*make)();
};
const Named kEstimators[] = {
    {"backward_difference", [] { return make<BackwardDifference>(); }},
    {"central_difference", [] { return make<PolynomialFitEstimator>(3, 2, 1); }},
    {"savitzky_golay_5_2", nullptr},
    {"savitzky_golay_9_2", nullptr},
    {"savitzky_golay_9_4", nullptr},
    {"savitzky_golay_15_3", nullptr},
    {"savitzky_golay_end_7_2", nullptr},
    {"savitzky_golay_end_15_3", nullptr},
    {"kalman", [] { return make<KalmanEstimator>(1e3, 1e-5); }},
    {"kalman_smooth", [] { return make<KalmanEstimator>(10.0, 1e-4); }},
};

}  // namespace

const std::vector<std::string>& derivative_estimator_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Named& e : kEstimators) out.push_back(e.name);
    return out;
  }();
  return names;
}

std::unique_ptr<DerivativeEstimator> make_derivative_estimator(const std::string& name) {
  for (const Named& e : kEstimators)
    if (e.make && name == e.name) return e.make();
  if (std::unique_ptr<DerivativeEstimator> fit = savitzky_golay(name)) return fit;
  std::string known;
  for (const Named& e : kEstimators) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw std::invalid_argument("unknown derivative estimator '" + name + "' (known: " + known +
                              "; savitzky_golay[_end]_<window>_<order> for other windows)");
}

}  // namespace mbk
