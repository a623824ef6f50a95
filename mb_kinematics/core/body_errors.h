// First-order standard errors of each body's angular acceleration alpha_k and mass-center
// acceleration a_k from independent errors of the joint velocities y_r and accelerations y_r'
// (coordinate-derivative speeds, y = q': mbk bag's estimates and their error bars), through the
// partial velocity arrays (doc/method.md 5). With alpha_k = sum_r (omega_kr y_r' + omega_kr' y_r)
// and a_k = sum_r (v_kr y_r' + v_kr' y_r) (eq. 4.7.7-4.7.12), the sensitivities are
//   d alpha_k / d y_r' = omega_kr,   d alpha_k / d y_r = 2 omega_kr' + omega_kr x omega_k,
//   d a_k / d y_r' = v_kr,           d a_k / d y_r = 2 v_kr',
// since d omega_k / d q_r = omega_kr' + omega_kr x omega_k and d v_k / d q_r = v_kr' (Lagrange's
// identity); each R component's variance sums the squared sensitivities times the variances.
// Velocity and acceleration errors are taken as uncorrelated (a centred fit's first-derivative
// weights are odd, its second's even). No allocation.
#pragma once

#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/partial_velocity.h"

namespace mbk {

// Body k's standard errors from its columns in pv and data's omega_k (partial_velocity_kinematics
// of the state); speed_se[r], speed_dot_se[r]: standard errors of y_r and y_r'.
template <typename S>
void body_acceleration_error(const PartialVelocities<S>& pv, const Data<S>& data, int k,
                             const S* speed_se, const S* speed_dot_se, Vec3<S>& alpha_se,
                             Vec3<S>& acceleration_se) {
  Vec3<S> alpha_var = Vec3<S>::Zero(), a_var = Vec3<S>::Zero();
  for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i) {
    const S sv = speed_se[pv.speed[i]], sa = speed_dot_se[pv.speed[i]];
    const Vec3<S> alpha_y = S(2) * pv.omega_dot[i] + pv.omega[i].cross(data.omega[k]);
    const Vec3<S> a_y = S(2) * pv.velocity_dot[i];
    alpha_var +=
        (pv.omega[i].array().square() * sa * sa + alpha_y.array().square() * sv * sv).matrix();
    a_var += (pv.velocity[i].array().square() * sa * sa + a_y.array().square() * sv * sv).matrix();
  }
  alpha_se = alpha_var.cwiseSqrt();
  acceleration_se = a_var.cwiseSqrt();
}

// pv and data from partial_velocity_kinematics of the state. Out: per body k (index 0 unused),
// the standard error of each R component of alpha_k and a_k.
template <typename S>
void body_acceleration_errors(const Model& model, const PartialVelocities<S>& pv,
                              const Data<S>& data, const S* speed_se, const S* speed_dot_se,
                              std::vector<Vec3<S>>& alpha_se,
                              std::vector<Vec3<S>>& acceleration_se) {
  const int n = model.body_count();
  alpha_se.assign(n + 1, Vec3<S>::Zero());
  acceleration_se.assign(n + 1, Vec3<S>::Zero());
  for (int k = 1; k <= n; ++k)
    body_acceleration_error(pv, data, k, speed_se, speed_dot_se, alpha_se[k], acceleration_se[k]);
}

// The same from the state, each body's as its columns are done: with a streamed pv
// (PartialVelocities(model, kStreamed)), in memory for the bodies alive at once, not N x depth.
// Of data, only the poses and omega_k are set (DataSums::kOmega).
template <typename S>
void body_acceleration_errors(const Model& model, const JointState<S>& state,
                              PartialVelocities<S>& pv, Data<S>& data, const S* speed_se,
                              const S* speed_dot_se, std::vector<Vec3<S>>& alpha_se,
                              std::vector<Vec3<S>>& acceleration_se) {
  const int n = model.body_count();
  alpha_se.assign(n + 1, Vec3<S>::Zero());
  acceleration_se.assign(n + 1, Vec3<S>::Zero());
  partial_velocity_kinematics(
      model, state, pv, data, Level::kAcceleration,
      [&](int k) {
        body_acceleration_error(pv, data, k, speed_se, speed_dot_se, alpha_se[k],
                                acceleration_se[k]);
      },
      DataSums::kOmega);  // the errors read the columns and omega_k alone
}

}  // namespace mbk
