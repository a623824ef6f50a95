// Three-vectors of double in four-lane vectors (GCC vector extensions; lane 3 unused), for the
// revolute kernels of forward_kinematics' AVX2 copy (fast_kernels_avx2.h, MBK_AVX2_DISPATCH): each
// operation once on 256 bits. Each lane does what Eigen's code does to that coordinate, in the
// same order, with no fused multiply-add: the results are the portable update's bit for bit
// (Formulations.CpuDispatchIsThePortableUpdate).
#pragma once

#include <cstring>
#ifdef MBK_AVX2_DISPATCH
#include <immintrin.h>
#endif

#include "mb_kinematics/core/types.h"

#ifdef MBK_AVX2_DISPATCH
#define MBK_VEC4 1
// Every function that handles these vectors is compiled for AVX2 and inlined into the AVX2 copy.
#define MBK_AVX2 __attribute__((target("avx2")))

namespace mbk {
namespace detail {
namespace v4 {

typedef double V4 __attribute__((vector_size(32)));

MBK_AVX2 inline V4 splat(double x) { return V4{x, x, x, x}; }

// *p in every lane: one load (GCC folds it into vbroadcastsd). A plain load, not the intrinsic
// _mm256_broadcast_sd(p): GCC's loop optimizer does not see through the intrinsic's pointer, and
// over the loop over bodies keeps one to each coordinate of the constants (body_step.h offset,
// mass_center) in a register of its own, each stepped once per body.
MBK_AVX2 inline V4 splat_at(const double* p) { return splat(*p); }

// Lane 3 zero. Two loads, of 16 and 8 bytes, that match store3's stores (a load of what the
// body before stored is forwarded from the store buffer), and an insert.
MBK_AVX2 inline V4 load3(const double* p) {
  const __m256d xy = _mm256_castpd128_pd256(_mm_loadu_pd(p));
  return (V4)_mm256_insertf128_pd(xy, _mm_load_sd(p + 2), 1);
}

MBK_AVX2 inline void store3(double* p, V4 v) {
  p[0] = v[0];
  p[1] = v[1];
  p[2] = v[2];
}

// Four aligned doubles (a padded constant, body_step.h).
MBK_AVX2 inline V4 load4(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

#if defined(__clang__) || __GNUC__ >= 12
#define MBK_SHUFFLE(a, b, ...) __builtin_shufflevector(a, b, __VA_ARGS__)
#else
#define MBK_SHUFFLE(a, b, ...) \
  __builtin_shuffle(a, b, (long long __attribute__((vector_size(32)))){__VA_ARGS__})
#endif

// (y, z, x): lanes 1, 2, 0.
MBK_AVX2 inline V4 yzx(V4 a) { return MBK_SHUFFLE(a, a, 1, 2, 0, 3); }

// Lanes 0, 1, 3 of a, lane 2 of b.
MBK_AVX2 inline V4 z_of(V4 a, V4 b) { return MBK_SHUFFLE(a, b, 0, 1, 6, 3); }

// a x b as Eigen's cross computes each coordinate (a_y b_z - a_z b_y, ...): the lanes of
// a (b_y, b_z, b_x) - (a_y, a_z, a_x) b are the coordinates z, x, y.
MBK_AVX2 inline V4 cross(V4 a, V4 b) { return yzx(a * yzx(b) - yzx(a) * b); }

// A 3x3 matrix by columns (named, not an array: GCC keeps them in registers).
struct Cols {
  V4 c0, c1, c2;
};

template <int I>
MBK_AVX2 V4 col(const Cols& m) {
  if constexpr (I == 0) return m.c0;
  if constexpr (I == 1) return m.c1;
  if constexpr (I == 2) return m.c2;
}

MBK_AVX2 inline Cols load_cols(const Mat3<double>& m) {
  const double* p = m.data();
  return {load3(p), load3(p + 3), load3(p + 6)};
}

MBK_AVX2 inline void store_cols(Mat3<double>& m, const Cols& c) {
  double* p = m.data();
  store3(p, c.c0);
  store3(p + 3, c.c1);
  store3(p + 6, c.c2);
}

// a0 + a1 + a2 summed as Eigen's 3x3 products (matrix times vector or matrix, SSE2 packets of two
// rows) sum each coordinate: (a0 + a1) + a2 for x and y, a0 + (a1 + a2) = (a2 + a1) + a0 for z.
MBK_AVX2 inline V4 sum3(V4 a0, V4 a1, V4 a2) { return (z_of(a0, a2) + a1) + z_of(a2, a0); }

// m v with v's coordinates v[0], v[1], v[2] in memory.
MBK_AVX2 inline V4 times(const Cols& m, const double* v) {
  return sum3(m.c0 * splat_at(v), m.c1 * splat_at(v + 1), m.c2 * splat_at(v + 2));
}

// m v with v's coordinates in a register.
MBK_AVX2 inline V4 times(const Cols& m, V4 v) {
  return sum3(m.c0 * splat(v[0]), m.c1 * splat(v[1]), m.c2 * splat(v[2]));
}

}  // namespace v4
}  // namespace detail
}  // namespace mbk

#endif  // MBK_VEC4
