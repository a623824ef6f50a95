// Absolute kinematics by the O(N) outward recursion along the lower body array (doc/method.md 4).
#pragma once

#include <cassert>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {
namespace detail {

// Every this many joints of depth, S0K gets one Newton-Schulz step back to orthonormal:
// R <- R (3 I - R^T R) / 2. Rounding makes S0K = S0J SJK drift from orthonormal by about eps
// per joint, linearly with depth (README, "Numerical stability"); one step squares the drift
// away at the cost of two 3x3 products, here once per 32 levels (cheap on long chains, and
// never on the human model, whose depth is at most 6).
constexpr int kReorthonormalizeEvery = 32;

template <typename S>
void reorthonormalize(Mat3<S>& r) {
  const Mat3<S> rtr = r.transpose() * r;
  r = r * (S(1.5) * Mat3<S>::Identity() - S(0.5) * rtr);
}

// Orientation, origin and mass center of body k from its lower body's (doc/method.md 4); also
// returns d = S0J (q_k + s_k) and rho = S0K r_k, which the velocity terms reuse.
template <typename S>
void pose_step(const Body& body, int k, const JointMotion<S>& m, Data<S>& data, Vec3<S>& d,
               Vec3<S>& rho) {
  const int j = body.lower;
  data.rotation[k] = data.rotation[j] * m.rotation;  // S0K = S0J SJK
  if (body.depth % kReorthonormalizeEvery == 0) reorthonormalize(data.rotation[k]);
  d = data.rotation[j] * (body.joint.offset.cast<S>() + m.translation);  // S0J (q_k + s_k)
  data.origin[k] = data.origin[j] + d;                                   // eq. 4.6.2
  rho = data.rotation[k] * body.mass_center.cast<S>();                   // S0K r_k
  data.mass_center[k] = data.origin[k] + rho;
}

}  // namespace detail

// Computes, for every body k = 1..N in increasing order (so L(k) is done first), its
// orientation and origin, and with `level` its velocities and accelerations. No allocation.
template <typename S>
void forward_kinematics(const Model& model, const JointState<S>& state, Data<S>& data,
                        Level level = Level::kAcceleration) {
  assert(sized_for(data, model) && "forward_kinematics: Data made for another model");
  JointMotion<S> m;
  const bool velocities = level != Level::kPose;
  const bool accelerations = level == Level::kAcceleration;
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const int j = body.lower;
    const S* y = velocities ? state.velocity.data() + body.v_index : nullptr;
    joint_motion(body.joint, model.speeds, state.position.data() + body.q_index, y, m);
    Vec3<S> d, rho;
    detail::pose_step(body, k, m, data, d, rho);
    if (!velocities) continue;

    const Mat3<S>& s0j = data.rotation[j];

    const bool translates = m.linear_speeds > 0;         // the s_k' terms vanish otherwise
    Vec3<S> w = Vec3<S>::Zero(), sd0 = Vec3<S>::Zero();  // w_k in Bj; S0J s_k'
    for (int c = m.linear_speeds; c < m.speeds; ++c) w += m.angular[c] * y[c];
    if (translates) {
      Vec3<S> sd = Vec3<S>::Zero();
      for (int c = 0; c < m.linear_speeds; ++c) sd += m.linear[c] * y[c];
      sd0 = s0j * sd;
    }
    const Vec3<S> w0 = s0j * w;
    const Vec3<S>& omega_j = data.omega[j];
    data.omega[k] = omega_j + w0;                                                // eq. 4.4.6
    data.origin_velocity[k] = data.origin_velocity[j] + omega_j.cross(d) + sd0;  // doc/method.md 4
    data.mass_center_velocity[k] = data.origin_velocity[k] + data.omega[k].cross(rho);
    if (!accelerations) continue;

    const S* yd = state.acceleration.data() + body.v_index;
    Vec3<S> wd = Vec3<S>::Zero();  // w_k' in Bj
    for (int c = m.linear_speeds; c < m.speeds; ++c)
      wd += m.angular[c] * yd[c] + m.angular_dot[c] * y[c];
    const Vec3<S>& alpha_j = data.alpha[j];
    data.alpha[k] = alpha_j + s0j * wd + omega_j.cross(w0);  // eq. 4.5.1
    Vec3<S>& a_o = data.origin_acceleration[k];              // doc/method.md 4
    a_o = data.origin_acceleration[j] + alpha_j.cross(d) + omega_j.cross(omega_j.cross(d));
    if (translates) {
      Vec3<S> sdd = Vec3<S>::Zero();  // s_k'' in Bj
      for (int c = 0; c < m.linear_speeds; ++c) sdd += m.linear[c] * yd[c];
      a_o += S(2) * omega_j.cross(sd0) + s0j * sdd;
    }
    const Vec3<S>& omega_k = data.omega[k];
    data.mass_center_acceleration[k] =
        data.origin_acceleration[k] + data.alpha[k].cross(rho) + omega_k.cross(omega_k.cross(rho));
  }
}

}  // namespace mbk
