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

#include "mb_kinematics/core/body_update.h"  // first: MBK_AVX2_DISPATCH, which vec4.h reads
#include "mb_kinematics/core/vec4.h"

namespace mbk {
namespace detail {

#ifdef MBK_VEC4
namespace v4 {

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

}  // namespace v4

template <>
struct CrossProduct<v4::V4> {  // fixed_point's (point_kinematics.h) and body_update's
  MBK_AVX2 static void of(const v4::V4& a, const v4::V4& b, v4::V4& out) { out = v4::cross(a, b); }
};

template <>
struct Lanes<v4::V4> {  // body_update's registers: a 3-vector in four lanes, S0K in three
  using S = double;
  using Rotation = v4::Cols;
  struct Spin {
    v4::V4 omega{}, alpha{};
  };
  // Body k's omega and alpha at level L loaded (kRead), or zero registers to compute them in.
  template <Level L, bool kRead>
  MBK_AVX2 static Spin spin(const DataView<double>& data, int k) {
    Spin m;
    if constexpr (kRead && L != Level::kPose) m.omega = v4::load3(data.omega[k].data());
    if constexpr (kRead && L == Level::kAcceleration) m.alpha = v4::load3(data.alpha[k].data());
    return m;
  }
  MBK_AVX2 static void store(Vec3<double>& x, const v4::V4& v) { v4::store3(x.data(), v); }
  using Point = PointMotion<v4::V4>;
  // Body k's point of `arrays` at level L, loaded.
  template <Level L>
  MBK_AVX2 static Point point(const PointArrays<double>& arrays, int k) {
    Point m;
    m.position = v4::load3(arrays.position[k].data());
    if constexpr (L != Level::kPose) m.velocity = v4::load3(arrays.velocity[k].data());
    if constexpr (L == Level::kAcceleration)
      m.acceleration = v4::load3(arrays.acceleration[k].data());
    return m;
  }
  // The point body_update makes from `from`: made in from's registers (fixed_point_into in place),
  // then stored by store_point.
  template <Level L>
  MBK_AVX2 static Point& target(const PointArrays<double>&, int, Point& from) {
    return from;
  }
  template <Level L>
  MBK_AVX2 static void store_point(const PointArrays<double>& arrays, int k, const Point& m) {
    store(arrays.position[k], m.position);
    if constexpr (L != Level::kPose) store(arrays.velocity[k], m.velocity);
    if constexpr (L == Level::kAcceleration) store(arrays.acceleration[k], m.acceleration);
  }
  // rho = S0K r_k from the registers, or from Data where body_update reorthonormalized S0K.
  MBK_AVX2 static void mass_center_offset(const BodyStep& b, const Mat3<double>& s0k,
                                          const v4::Cols& turned, v4::V4& rho) {
    rho = v4::times_constant(b.reorthonormalize ? v4::load_cols(s0k) : turned, b.mass_center,
                             b.mass_center_shape);
  }
};

// The revolute kernels' terms on four-lane vectors (vec4.h): the sums of the kernels of
// fast_kernels.h, term for term and in the same order, so the same results bit for bit, in fewer
// instructions; body_update then runs on them.
namespace v4 {

// w = u q', wd = u q'' with u = S0J w_k / q', the joint's axis in R; S0K stored and kept in t,
// d = S0J q_k.
template <Level L>
MBK_AVX2 void turn_terms(const BodyStep& b, int k, const Cols& s0j, const Cols& s0k, V4 u,
                         const StateView<double>& state, const DataView<double>& data,
                         JointTerms<V4>& t) {
  store_cols(data.rotation[k], s0k);
  t.s0k = s0k;
  t.d = times_constant(s0j, b.offset, b.offset_shape);
  if constexpr (L != Level::kPose) t.w = u * splat_at(state.y + b.v_index);
  if constexpr (L == Level::kAcceleration) t.wd = u * splat_at(state.yd + b.v_index);
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

// Body k of a revolute joint (kernel K; fast_kernels.h kFourLanes): about coordinate axis I with
// C_k = I, S0K turns two columns of S0J and u is column I of S0J (axis_terms); about any axis
// with any C_k, S0K = S0J (P0 + c P1 + s P2) and u = S0J (C_k a) (revolute_terms). Then
// body_update on the four-lane terms.
template <Level L, JointKernel K>
MBK_AVX2 void revolute_step(const Model& model, const BodyStep& b, int k,
                            const StateView<double>& state, const DataView<double>& data) {
  const Cols s0j = load_cols(data.rotation[b.lower]);
  JointTerms<V4> t;
  if constexpr (K == JointKernel::kRevolute)
    turn_terms<L>(b, k, s0j,
                  folded_turn(model.steps.padded.data() + b.matrices, s0j, data.cosine + b.angle,
                              data.sine + b.angle),
                  L == Level::kPose ? V4{} : times(s0j, b.axis.data()), state, data, t);
  else
    turn_terms<L>(b, k, s0j,
                  turn_columns<kAxis<K>>(s0j, data.cosine + b.angle, data.sine + b.angle),
                  col<kAxis<K>>(s0j), state, data, t);
  body_update<L, JointMoves::kTurns>(b, k, t, data);
}

}  // namespace v4
#else
namespace v4 {  // declared only: without MBK_VEC4 no copy with kAvx2 is instantiated
template <Level L, JointKernel K>
void revolute_step(const Model& model, const BodyStep& b, int k, const StateView<double>& state,
                   const DataView<double>& data);
}  // namespace v4
#endif  // MBK_VEC4

}  // namespace detail
}  // namespace mbk
