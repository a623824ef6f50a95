// One body of the outward recursion (doc/method.md 4): body k from its lower body j = L(k) and
// its joint's terms (JointTerms), whichever kernel got them (fast_kernels.h). The recursion
// (kinematics.h) runs it for k = 1..N.
#pragma once

#include "mb_kinematics/core/body_step.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_views.h"
#include "mb_kinematics/core/point_kinematics.h"

namespace mbk {
namespace detail {

// A joint's share of body k's motion, in R components: d = S0J (q_k + s_k) (O_j to O_k), the
// relative angular velocity w = S0J w_k and w' part wd = S0J w_k', and sd = S0J s_k',
// sdd = S0J s_k''.
template <typename S>
struct JointTerms {
  Vec3<S> d, w, wd, sd, sdd;
};

// What a joint's terms hold: whether it turns body k (w, wd) and translates it (sd, sdd).
enum class JointMoves { kNone, kTurns, kTranslates, kTurnsAndTranslates };

// Body k once its joint has put S0K = S0J SJK into data.rotation[k] (doc/method.md 4): its
// angular velocity and acceleration, its origin O_k (the point at d of Bj, moved by S0J s_k' when
// the joint translates) and its mass center G_k (the point at rho = S0K r_k of Bk), each point
// with its velocity and acceleration (fixed_point). A zero d or r_k leaves the point as it was.
template <Level L, JointMoves M, typename S>
void body_update(const BodyStep& b, int k, const JointTerms<S>& t, const DataView<S>& data) {
  constexpr bool kTurns = M == JointMoves::kTurns || M == JointMoves::kTurnsAndTranslates;
  constexpr bool kTranslates = M == JointMoves::kTranslates || M == JointMoves::kTurnsAndTranslates;
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);  // doc/method.md 4, orientation
  const Vec3<S>&omega_j = data.omega[j], &alpha_j = data.alpha[j];
  if constexpr (L != Level::kPose) {
    data.omega[k] = omega_j;
    if constexpr (kTurns) data.omega[k] += t.w;  // eq. 4.4.6
  }
  if constexpr (L == Level::kAcceleration) {
    if constexpr (kTurns)
      data.alpha[k] = alpha_j + t.wd + omega_j.cross(t.w);  // eq. 4.5.1
    else
      data.alpha[k] = alpha_j;
  }
  const PointArrays<S> origins = data.origins();
  if (!kTranslates && b.offset_shape == VectorShape::kZero) {
    set_point<L>(origins, k, point_at<L>(origins, j));  // O_k = O_j
  } else {  // eq. 4.6.2: o_k = o_j + d_k, moving as the point d of Bj
    PointMotion<Vec3<S>> o = fixed_point<L>(point_at<L>(origins, j), omega_j, alpha_j, t.d);
    if constexpr (kTranslates && L != Level::kPose) {
      o.velocity += t.sd;                       // doc/method.md 4, origin velocity
      if constexpr (L == Level::kAcceleration)  // and acceleration
        o.acceleration += S(2) * omega_j.cross(t.sd) + t.sdd;
    }
    set_point<L>(origins, k, o);
  }
  const PointMotion<Vec3<S>> o = point_at<L>(origins, k);  // doc/method.md 4, mass center
  if (b.mass_center_shape == VectorShape::kZero) return set_point<L>(data.centers(), k, o);
  const Vec3<S> rho = times_constant(data.rotation[k], b.mass_center, b.mass_center_shape);
  set_point<L>(data.centers(), k, fixed_point<L>(o, data.omega[k], data.alpha[k], rho));
}

}  // namespace detail
}  // namespace mbk
