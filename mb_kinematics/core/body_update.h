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

// How body_update holds a 3-vector V while it works, and reads and writes Data's: here Eigen's
// Vec3<S>, the kernels' S0K read back from data.rotation[k]. The AVX2 copy's four-lane vectors
// (fast_kernels_avx2.h) specialize it: loads and stores of registers, S0K kept in them (each
// result written to `out`, as CrossProduct's, point_kinematics.h).
template <typename V>
struct Lanes {
  using S = typename V::Scalar;
  struct Rotation {};  // S0K as the kernel holds it: only in data.rotation[k]
  static void load(const V& x, V& out) { out = x; }
  static void store(V& x, const V& v) { x = v; }
  // rho = S0K r_k (doc/method.md 4, mass center), S0K once body_update has it in data.rotation[k].
  static void mass_center_offset(const BodyStep& b, const Mat3<S>& s0k, const Rotation&, V& rho) {
    rho = times_constant(s0k, b.mass_center, b.mass_center_shape);
  }
};

// A joint's share of body k's motion, in R components: d = S0J (q_k + s_k) (O_j to O_k), the
// relative angular velocity w = S0J w_k and w' part wd = S0J w_k', and sd = S0J s_k',
// sdd = S0J s_k''; S0K as the kernel holds it (Lanes). V: Vec3<S>, or the AVX2 copy's.
template <typename V>
struct JointTerms {
  V d, w, wd, sd, sdd;
  typename Lanes<V>::Rotation s0k;
};

// What a joint's terms hold: whether it turns body k (w, wd) and translates it (sd, sdd).
enum class JointMoves { kNone, kTurns, kTranslates, kTurnsAndTranslates };

// The coordinate axis (0, 1, 2: x, y, z) of a revolute joint's kernel kRevoluteX, Y or Z.
template <JointKernel K>
constexpr int kAxis = K == JointKernel::kRevoluteX   ? 0
                      : K == JointKernel::kRevoluteY ? 1
                                                     : 2;

// The point of body k (origin or mass center) at level L from Data, and back (the parts L leaves
// out are neither read nor written).
template <Level L, typename V, typename S>
PointMotion<V> load_point(const PointArrays<S>& arrays, int k) {
  PointMotion<V> m;
  Lanes<V>::load(arrays.position[k], m.position);
  if constexpr (L != Level::kPose) Lanes<V>::load(arrays.velocity[k], m.velocity);
  if constexpr (L == Level::kAcceleration) Lanes<V>::load(arrays.acceleration[k], m.acceleration);
  return m;
}

template <Level L, typename V, typename S>
void store_point(const PointArrays<S>& arrays, int k, const PointMotion<V>& m) {
  Lanes<V>::store(arrays.position[k], m.position);
  if constexpr (L != Level::kPose) Lanes<V>::store(arrays.velocity[k], m.velocity);
  if constexpr (L == Level::kAcceleration) Lanes<V>::store(arrays.acceleration[k], m.acceleration);
}

// Body k once its joint has put S0K = S0J SJK into data.rotation[k] (doc/method.md 4): its
// angular velocity and acceleration, its origin O_k (the point at d of Bj, moved by S0J s_k' when
// the joint translates) and its mass center G_k (the point at rho = S0K r_k of Bk), each point
// with its velocity and acceleration (fixed_point). A zero d or r_k leaves the point as it was.
template <Level L, JointMoves M, typename V, typename S>
void body_update(const BodyStep& b, int k, const JointTerms<V>& t, const DataView<S>& data) {
  using Lane = Lanes<V>;
  using Cross = CrossProduct<V>;
  constexpr bool kTurns = M == JointMoves::kTurns || M == JointMoves::kTurnsAndTranslates;
  constexpr bool kTranslates = M == JointMoves::kTranslates || M == JointMoves::kTurnsAndTranslates;
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);  // doc/method.md 4, orientation
  V omega_j{}, alpha_j{}, omega_k{}, alpha_k{};
  if constexpr (L != Level::kPose) {
    Lane::load(data.omega[j], omega_j);
    omega_k = omega_j;
    if constexpr (kTurns) omega_k = omega_j + t.w;  // eq. 4.4.6
    Lane::store(data.omega[k], omega_k);
  }
  if constexpr (L == Level::kAcceleration) {
    Lane::load(data.alpha[j], alpha_j);
    alpha_k = alpha_j;
    if constexpr (kTurns) {
      V omega_w;
      Cross::of(omega_j, t.w, omega_w);
      alpha_k = (alpha_j + t.wd) + omega_w;  // eq. 4.5.1
    }
    Lane::store(data.alpha[k], alpha_k);
  }
  const PointArrays<S> origins = data.origins();
  PointMotion<V> o = load_point<L, V>(origins, j);  // O_k = O_j when d = 0
  if (kTranslates || b.offset_shape != VectorShape::kZero) {
    o = fixed_point<L>(o, omega_j, alpha_j, t.d);  // eq. 4.6.2: o_k = o_j + d_k, point d of Bj
    if constexpr (kTranslates && L != Level::kPose) {
      o.velocity = o.velocity + t.sd;             // doc/method.md 4, origin velocity
      if constexpr (L == Level::kAcceleration) {  // and acceleration
        V omega_sd;
        Cross::of(omega_j, t.sd, omega_sd);
        o.acceleration = o.acceleration + (typename Lane::S(2) * omega_sd + t.sdd);
      }
    }
  }
  store_point<L>(origins, k, o);
  if (b.mass_center_shape != VectorShape::kZero) {  // else G_k = O_k
    V rho;                                          // S0K r_k (doc/method.md 4, mass center)
    Lane::mass_center_offset(b, data.rotation[k], t.s0k, rho);
    o = fixed_point<L>(o, omega_k, alpha_k, rho);
  }
  store_point<L>(data.centers(), k, o);
}

}  // namespace detail
}  // namespace mbk
