// Shared by the core's numerical tests: both formulations on one state, the fourth-order central
// difference, and the error scales the tolerances are relative to.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"

namespace mbk_test {

// Fourth-order central difference on the stencil t + offset * h:
//   f'(t) = (f(t-2h) - 8 f(t-h) + 8 f(t+h) - f(t+2h)) / (12 h) + O(h^4 f^(5)).
constexpr int kStencil = 4;
constexpr double kStencilOffsets[kStencil] = {-2.0, -1.0, 1.0, 2.0};
constexpr double kStencilWeights[kStencil] = {1.0, -8.0, 8.0, -1.0};

// `sample(i)` is f at t + kStencilOffsets[i] * h.
template <typename T>
T central_difference(const std::function<T(int)>& sample, double h) {
  T sum = kStencilWeights[0] * sample(0);
  for (int i = 1; i < kStencil; ++i) sum += kStencilWeights[i] * sample(i);
  return sum / (12.0 * h);
}

// The angular velocity w with [w]x = skew part of W (W = S' S^T, doc/method.md 6).
inline mbk::Vec3<double> vee_of_skew_part(const mbk::Mat3<double>& w) {
  const mbk::Mat3<double> s = 0.5 * (w - w.transpose());
  return mbk::Vec3<double>(s(2, 1), s(0, 2), s(1, 0));
}

// Both formulations (doc/method.md 4 and 5) on one state.
struct BothFormulations {
  mbk::Data<double> recursive;
  mbk::Data<double> partial;
  mbk::PartialVelocities<double> pv;

  explicit BothFormulations(const mbk::Model& model)
      : recursive(model), partial(model), pv(model) {}

  void run(const mbk::Model& model, const mbk::JointState<double>& state,
           mbk::Level level = mbk::Level::kAcceleration) {
    mbk::forward_kinematics(model, state, recursive, level);
    mbk::partial_velocity_kinematics(model, state, pv, partial, level);
  }
};

// Magnitude scales of body k's velocity-level sums, sum over r of |column_r| |y_r| (and for the
// accelerations |column_r| |y_r'| + |column_r'| |y_r|): the rounding error of either
// formulation is a modest multiple of eps times these (doc/method.md 5 sums over these columns).
struct SumScales {
  double omega = 0, velocity = 0, origin_velocity = 0, alpha = 0, acceleration = 0,
         origin_acceleration = 0;
};

template <typename S>
SumScales sum_scales(const mbk::PartialVelocities<S>& pv, const mbk::JointState<S>& state, int k) {
  using std::abs;
  SumScales s;
  for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i) {
    const double y = static_cast<double>(abs(state.velocity[pv.speed[i]]));
    const double yd = static_cast<double>(abs(state.acceleration[pv.speed[i]]));
    auto n = [](const mbk::Vec3<S>& v) { return static_cast<double>(v.norm()); };
    s.omega += n(pv.omega[i]) * y;
    s.velocity += n(pv.velocity[i]) * y;
    s.origin_velocity += n(pv.origin_velocity[i]) * y;
    s.alpha += n(pv.omega[i]) * yd + n(pv.omega_dot[i]) * y;
    s.acceleration += n(pv.velocity[i]) * yd + n(pv.velocity_dot[i]) * y;
    s.origin_acceleration += n(pv.origin_velocity[i]) * yd + n(pv.origin_velocity_dot[i]) * y;
  }
  return s;
}

}  // namespace mbk_test
