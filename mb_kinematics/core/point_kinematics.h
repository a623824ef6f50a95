// The motion of a point fixed in a body, every vector in R components: the one formula that the
// recursion (its origins and mass centers, and its AVX2 copy's), the outputs in a body's frame,
// the system's root link and the floating base all use.
#pragma once

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

// A point's position, velocity and acceleration. V: Vec3<S>, or a four-lane vector of the AVX2
// copy (vec4.h).
template <typename V>
struct PointMotion {
  V position{}, velocity{}, acceleration{};
};

namespace detail {

// a x b for fixed_point's vectors: Eigen's; fast_kernels_avx2.h adds its four-lane vectors'
// (written to `out`: a four-lane vector returned by value from code not compiled for AVX would
// change the ABI).
template <typename V>
struct CrossProduct {
  static void of(const V& a, const V& b, V& out) { out = a.cross(b); }
};

}  // namespace detail

// P at rho from the point O of a body turning at omega, alpha, O moving as `o` (doc/method.md 4,
// mass center): p = o + rho, v = v_o + omega x rho, a = a_o + alpha x rho + omega x (omega x rho).
// L: kPose gives p alone, kVelocity p and v. O and P: a point's position, velocity and
// acceleration (a PointMotion, or the recursion's references into Data: body_update.h); P may be
// O itself (each part of O is read before P's is written).
template <Level L = Level::kAcceleration, typename O, typename V, typename P>
void fixed_point_into(const O& o, const V& omega, const V& alpha, const V& rho, P&& p) {
  using Cross = detail::CrossProduct<V>;
  p.position = o.position + rho;
  if constexpr (L != Level::kPose) {
    V omega_rho, alpha_rho, omega_omega_rho;
    Cross::of(omega, rho, omega_rho);
    p.velocity = o.velocity + omega_rho;
    if constexpr (L == Level::kAcceleration) {
      Cross::of(alpha, rho, alpha_rho);
      Cross::of(omega, omega_rho, omega_omega_rho);
      p.acceleration = (o.acceleration + alpha_rho) + omega_omega_rho;
    }
  }
}

template <Level L = Level::kAcceleration, typename V>
PointMotion<V> fixed_point(const PointMotion<V>& o, const V& omega, const V& alpha, const V& rho) {
  PointMotion<V> p;
  fixed_point_into<L>(o, omega, alpha, rho, p);
  return p;
}

// The point of body k at r from O_k (components in Bk: r = r_k is G_k) from `data`, at level L.
template <Level L = Level::kAcceleration, typename S>
PointMotion<Vec3<S>> body_point(const Data<S>& data, int k, const Vec3<S>& r) {
  const PointMotion<Vec3<S>> o{data.origin[k], data.origin_velocity[k],
                               data.origin_acceleration[k]};
  const Vec3<S> rho = detail::product<S>(data.rotation[k], r);  // S0K r
  return fixed_point<L>(o, data.omega[k], data.alpha[k], rho);
}

}  // namespace mbk
