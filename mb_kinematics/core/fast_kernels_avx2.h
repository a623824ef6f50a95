// The AVX2 copy's revolute kernels (forward_kinematics_avx2 in kinematics.h, chosen at run time
// on x86-64 CPUs with AVX2: MBK_AVX2_DISPATCH).
// What it speeds up: revolute joints (about x, y, z or any axis) at velocity and acceleration
// level, the chains' and the URDF models' joints: each 3-vector (a column of S0J or S0K, omega,
// alpha, a point's position, velocity and acceleration) is one 256-bit register (vec4.h), a
// cross product three lane turns, two products and a difference (doc/speed.md, "How the update
// is fast").
// How it is checked: each lane repeats what fast_kernels.h's Eigen code does to that coordinate,
// in its order and without fused multiply-add, so the results are the portable update's bit for
// bit (Formulations.CpuDispatchIsThePortableUpdate, test/core/finite_difference_test.cc), and
// test/core/generic_kernel_test.cc checks every kernel, this copy included (what
// forward_kinematics runs on this machine), against the generic path (motion_step).
#pragma once

#include "mb_kinematics/core/kinematics_views.h"  // first: MBK_AVX2_DISPATCH, which vec4.h reads
#include "mb_kinematics/core/vec4.h"

namespace mbk {
namespace detail {

#ifdef MBK_VEC4
template <>
struct CrossProduct<v4::V4> {  // fixed_point's (point_kinematics.h)
  MBK_AVX2 static void of(const v4::V4& a, const v4::V4& b, v4::V4& out) { out = v4::cross(a, b); }
};

// The revolute kernels of the AVX2 copy on four-lane vectors (vec4.h): the sums of the kernels
// of fast_kernels.h, term for term and in the same order, so the same results bit for bit, in fewer
// instructions.
namespace v4 {

// A body's omega and alpha, in registers.
struct BodySpin {
  V4 omega{}, alpha{};
};

// A point's motion (PointArrays, kinematics_views.h) in registers, and back.
template <Level L>
MBK_AVX2 PointMotion<V4> load_point(const PointArrays<double>& arrays, int k) {
  PointMotion<V4> m;
  m.position = load3(arrays.position[k].data());
  if constexpr (L != Level::kPose) m.velocity = load3(arrays.velocity[k].data());
  if constexpr (L == Level::kAcceleration) m.acceleration = load3(arrays.acceleration[k].data());
  return m;
}

template <Level L>
MBK_AVX2 void store_point(const PointArrays<double>& arrays, int k, const PointMotion<V4>& m) {
  store3(arrays.position[k].data(), m.position);
  if constexpr (L != Level::kPose) store3(arrays.velocity[k].data(), m.velocity);
  if constexpr (L == Level::kAcceleration) store3(arrays.acceleration[k].data(), m.acceleration);
}

// m v for a constant v of the given shape (times_constant, kinematics_views.h).
MBK_AVX2 inline V4 times_constant(const Cols& m, const Vec3<double>& v, VectorShape shape) {
  if (shape == VectorShape::kDense) return times(m, v.data());  // first: random offsets
  switch (shape) {
    case VectorShape::kZero:
      return V4{};
    case VectorShape::kX:
      return m.c0 * splat_at(v.data());
    case VectorShape::kY:
      return m.c1 * splat_at(v.data() + 1);
    case VectorShape::kZ:
      return m.c2 * splat_at(v.data() + 2);
    case VectorShape::kDense:
      break;
  }
  return times(m, v.data());
}

// omega_k = omega_j + w (eq. 4.4.6), alpha_k = alpha_j + wd + omega_j x w (eq. 4.5.1), with
// w = u q', wd = u q'': u = S0J w_k / q', the joint's axis in R; v: the joint's speed.
template <Level L>
MBK_AVX2 BodySpin turned_spin(const BodySpin& j, V4 u, const StateView<double>& state, int v) {
  BodySpin k;
  if constexpr (L != Level::kPose) {
    const V4 w = u * splat_at(state.y + v);
    k.omega = j.omega + w;
    if constexpr (L == Level::kAcceleration)
      k.alpha = (j.alpha + u * splat_at(state.yd + v)) + cross(j.omega, w);
  }
  return k;
}

// Stores S0K (reorthonormalized at its depth, body_update) and returns S0K r_k.
MBK_AVX2 inline V4 store_rotation(const BodyStep& b, int k, const Cols& s0k,
                                  const DataView<double>& data) {
  store_cols(data.rotation[k], s0k);
  if (!b.reorthonormalize) return times_constant(s0k, b.mass_center, b.mass_center_shape);
  reorthonormalize(data.rotation[k]);
  return times_constant(load_cols(data.rotation[k]), b.mass_center, b.mass_center_shape);
}

// Body k of a revolute joint (body_update): S0K, its spin from u (turned_spin), O_k = O_j +
// S0J q_k and G_k = O_k + S0K r_k with their motion (fixed_point; r = 0 leaves the point's).
template <Level L>
MBK_AVX2 void revolute_update(const BodyStep& b, int k, const Cols& s0j, const Cols& s0k, V4 u,
                              const StateView<double>& state, const DataView<double>& data) {
  const int j = b.lower;
  const V4 rho = store_rotation(b, k, s0k, data);
  BodySpin spin_j;
  if constexpr (L != Level::kPose) spin_j.omega = load3(data.omega[j].data());
  if constexpr (L == Level::kAcceleration) spin_j.alpha = load3(data.alpha[j].data());
  const BodySpin spin_k = turned_spin<L>(spin_j, u, state, b.v_index);
  if constexpr (L != Level::kPose) store3(data.omega[k].data(), spin_k.omega);
  if constexpr (L == Level::kAcceleration) store3(data.alpha[k].data(), spin_k.alpha);
  PointMotion<V4> point = load_point<L>(data.origins(), j);
  if (b.offset_shape != VectorShape::kZero)  // fixed_point: point_kinematics.h
    point = fixed_point<L>(point, spin_j.omega, spin_j.alpha,
                           times_constant(s0j, b.offset, b.offset_shape));
  store_point<L>(data.origins(), k, point);
  if (b.mass_center_shape != VectorShape::kZero)
    point = fixed_point<L>(point, spin_k.omega, spin_k.alpha, rho);
  store_point<L>(data.centers(), k, point);
}

// S0K = S0J SJK for a turn (cos, sin at c, s) about coordinate axis I (turn_columns).
template <int I>
MBK_AVX2 Cols turn_columns(const Cols& s0j, const double* c, const double* s) {
  constexpr int a = (I + 1) % 3, b = (I + 2) % 3;
  const V4 cos = splat_at(c), sin = splat_at(s);
  const V4 turned_a = cos * col<a>(s0j) + sin * col<b>(s0j);
  const V4 turned_b = cos * col<b>(s0j) - sin * col<a>(s0j);
  if constexpr (I == 0) return {s0j.c0, turned_a, turned_b};
  if constexpr (I == 1) return {turned_b, s0j.c1, turned_a};
  if constexpr (I == 2) return {turned_a, turned_b, s0j.c2};
}

// Column i of S0J SJK with SJK = P0 + c P1 + s P2 (folded_turn); p: P0 P1 P2 padded.
MBK_AVX2 inline V4 folded_column(const PaddedMat3* p, int i, const Cols& s0j, V4 cos, V4 sin) {
  const V4 sjk = (load4(p[0].col[i]) + cos * load4(p[1].col[i])) + sin * load4(p[2].col[i]);
  return times(s0j, sjk);
}

MBK_AVX2 inline Cols folded_turn(const PaddedMat3* p, const Cols& s0j, const double* c,
                                 const double* s) {
  const V4 cos = splat_at(c), sin = splat_at(s);
  return {folded_column(p, 0, s0j, cos, sin), folded_column(p, 1, s0j, cos, sin),
          folded_column(p, 2, s0j, cos, sin)};
}

// Revolute joint about coordinate axis I, C_k = I: u = column I of S0J.
template <Level L, int I>
MBK_AVX2 void revolute_axis_step(const BodyStep& b, int k, const StateView<double>& state,
                                 const DataView<double>& data) {
  const Cols s0j = load_cols(data.rotation[b.lower]);
  const Cols s0k = turn_columns<I>(s0j, data.cosine + b.angle, data.sine + b.angle);
  revolute_update<L>(b, k, s0j, s0k, col<I>(s0j), state, data);
}

// Revolute joint about any axis with any C_k: u = S0J (C_k a).
template <Level L>
MBK_AVX2 void revolute_step(const Model& model, const BodyStep& b, int k,
                            const StateView<double>& state, const DataView<double>& data) {
  const Cols s0j = load_cols(data.rotation[b.lower]);
  const Cols s0k = folded_turn(model.steps.padded.data() + b.matrices, s0j, data.cosine + b.angle,
                               data.sine + b.angle);
  const V4 u = L == Level::kPose ? V4{} : times(s0j, b.axis.data());
  revolute_update<L>(b, k, s0j, s0k, u, state, data);
}

}  // namespace v4
#else
namespace v4 {  // declared only: without MBK_VEC4 no copy with kAvx2 is instantiated
template <Level L, int I>
void revolute_axis_step(const BodyStep& b, int k, const StateView<double>& state,
                        const DataView<double>& data);
template <Level L>
void revolute_step(const Model& model, const BodyStep& b, int k, const StateView<double>& state,
                   const DataView<double>& data);
}  // namespace v4
#endif  // MBK_VEC4

}  // namespace detail
}  // namespace mbk
