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

// Where body_update keeps the vectors of Data it reads and writes while it works on body k.
// Here, for Eigen's Vec3<S>: in Data itself. Spin and Point are references into Data, so each
// result is written where it belongs as it is computed and the stores have nothing left to do;
// the kernels' S0K is read back from data.rotation[k]. The AVX2 copy's four-lane vectors
// (fast_kernels_avx2.h) specialize it: registers, loaded by spin and point, written back to Data
// by store and store_point, S0K kept in them.
template <typename V>
struct Lanes {
  using S = typename V::Scalar;
  struct Rotation {};  // S0K as the kernel holds it: only in data.rotation[k]
  struct Spin {        // a body's angular velocity omega and acceleration alpha: Data's own
    V &omega, &alpha;
  };
  // Body k's omega and alpha at level L, to read (kRead) or to write.
  template <Level L, bool kRead>
  static Spin spin(const DataView<S>& data, int k) {
    return {data.omega[k], data.alpha[k]};
  }
  static void store(V&, const V&) {}  // Data's x = v: already there
  struct Point {                      // a point's position, velocity and acceleration: Data's own
    V &position, &velocity, &acceleration;
  };
  // Body k's point of `arrays` (its origin or mass center) at level L, to read.
  template <Level L>
  static Point point(const PointArrays<S>& arrays, int k) {
    return {arrays.position[k], arrays.velocity[k], arrays.acceleration[k]};
  }
  // The point body_update makes from the point `from` and then stores as body k's point of
  // `arrays`: body k's point in Data.
  template <Level L>
  static Point target(const PointArrays<S>& arrays, int k, Point&) {
    return point<L>(arrays, k);
  }
  // Data's body k's point of `arrays` = p at level L: already there.
  template <Level L>
  static void store_point(const PointArrays<S>&, int, const Point&) {}
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

// q = p at level L (the parts L leaves out neither read nor written).
template <Level L, typename P, typename Q>
void copy_point(const P& p, Q& q) {
  q.position = p.position;
  if constexpr (L != Level::kPose) q.velocity = p.velocity;
  if constexpr (L == Level::kAcceleration) q.acceleration = p.acceleration;
}

// Body k once its joint has put S0K = S0J SJK into data.rotation[k] (doc/method.md 4): its
// angular velocity and acceleration, its origin O_k (the point at d of Bj, moved by S0J s_k' when
// the joint translates) and its mass center G_k (the point at rho = S0K r_k of Bk), each point
// with its velocity and acceleration (fixed_point_into). A zero d or r_k leaves the point as it
// was. Body j = L(k)'s vectors are read and body k's written as Lanes holds them: Data's own
// (Eigen's), or registers loaded and then stored (the AVX2 copy's).
template <Level L, JointMoves M, typename V, typename S>
void body_update(const BodyStep& b, int k, const JointTerms<V>& t, const DataView<S>& data) {
  using Lane = Lanes<V>;
  using Cross = CrossProduct<V>;
  constexpr bool kTurns = M == JointMoves::kTurns || M == JointMoves::kTurnsAndTranslates;
  constexpr bool kTranslates = M == JointMoves::kTranslates || M == JointMoves::kTurnsAndTranslates;
  constexpr bool kMoving = L != Level::kPose, kAccelerating = L == Level::kAcceleration;
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);  // doc/method.md 4, orientation
  typename Lane::Spin spin_j = Lane::template spin<L, true>(data, j);   // read
  typename Lane::Spin spin_k = Lane::template spin<L, false>(data, k);  // written
  auto &omega_j = spin_j.omega, &alpha_j = spin_j.alpha;
  auto &omega_k = spin_k.omega, &alpha_k = spin_k.alpha;
  if constexpr (kMoving) {
    if constexpr (kTurns)
      omega_k = omega_j + t.w;  // eq. 4.4.6
    else
      omega_k = omega_j;
    Lane::store(data.omega[k], omega_k);
  }
  if constexpr (kAccelerating) {
    if constexpr (kTurns) {
      V omega_w;
      Cross::of(omega_j, t.w, omega_w);
      alpha_k = (alpha_j + t.wd) + omega_w;  // eq. 4.5.1
    } else {
      alpha_k = alpha_j;
    }
    Lane::store(data.alpha[k], alpha_k);
  }
  const PointArrays<S> origins = data.origins();
  typename Lane::Point o_j = Lane::template point<L>(origins, j);
  auto&& o_k = Lane::template target<L>(origins, k, o_j);  // Data's O_k, or o_j's registers
  if (kTranslates || b.offset_shape != VectorShape::kZero) {
    fixed_point_into<L>(o_j, omega_j, alpha_j, t.d, o_k);  // eq. 4.6.2: o_k = o_j + d_k
    if constexpr (kTranslates && kMoving) {
      o_k.velocity = o_k.velocity + t.sd;  // doc/method.md 4, origin velocity
      if constexpr (kAccelerating) {       // and acceleration
        V omega_sd;
        Cross::of(omega_j, t.sd, omega_sd);
        o_k.acceleration = o_k.acceleration + (typename Lane::S(2) * omega_sd + t.sdd);
      }
    }
  } else {
    copy_point<L>(o_j, o_k);  // O_k = O_j
  }
  Lane::template store_point<L>(origins, k, o_k);
  const PointArrays<S> centers = data.centers();
  auto&& g_k = Lane::template target<L>(centers, k, o_k);  // Data's G_k, or o_k's registers
  if (b.mass_center_shape != VectorShape::kZero) {
    V rho;  // S0K r_k (doc/method.md 4, mass center)
    Lane::mass_center_offset(b, data.rotation[k], t.s0k, rho);
    fixed_point_into<L>(o_k, omega_k, alpha_k, rho, g_k);
  } else {
    copy_point<L>(o_k, g_k);  // G_k = O_k
  }
  Lane::template store_point<L>(centers, k, g_k);
}

}  // namespace detail
}  // namespace mbk
