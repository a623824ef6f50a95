#include "mb_kinematics/core/system_kinematics.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

// The vector helpers below are always inlined into the AVX2 function: no vector crosses a call,
// so GCC's note on the ABI of 32-byte vectors without AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace mbk {

std::vector<std::string> bodies_without_inertia(const Model& model) {
  std::vector<std::string> names;
  for (int k = 0; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    if (lacks_inertia(body)) names.push_back(body.name);
  }
  return names;
}

bool inertias_known(const Model& model) {
  for (int k = 0; k <= model.body_count(); ++k)
    if (lacks_inertia(model.bodies[k])) return false;
  return true;
}

#if defined(__x86_64__)
namespace {
namespace system_avx2 {  // apart from the names of the files beside it in a unity build

// A Vec3 (or a column of a Mat3) in lanes 0-2, lane 3 zero; and back.
#define MBK_AVX2 __attribute__((target("avx2"), always_inline)) inline
MBK_AVX2 __m256d load3(const double* x) {
  return _mm256_maskload_pd(x, _mm256_setr_epi64x(-1, -1, -1, 0));
}
MBK_AVX2 void store3(const __m256d& x, Vec3<double>& out) {
  _mm256_maskstore_pd(out.data(), _mm256_setr_epi64x(-1, -1, -1, 0), x);
}
MBK_AVX2 __m256d mul(const __m256d& a, const __m256d& b) { return _mm256_mul_pd(a, b); }
MBK_AVX2 __m256d add(const __m256d& a, const __m256d& b) { return _mm256_add_pd(a, b); }
MBK_AVX2 __m256d sub(const __m256d& a, const __m256d& b) { return _mm256_sub_pd(a, b); }

// c0 x0 + c1 x1 + c2 x2 (a Mat3 of columns c times x) summed in Eigen's order (a Mat3 times a
// Vec3 at -O3 or -O1): ((a_i0 x0 + a_i1 x1) + a_i2 x2) in rows 0 and 1, its packet; with
// `last_apart`, a_20 x0 + (a_21 x1 + a_22 x2) in row 2, its coefficient alone (Eigen's halving
// reduction); without, row 2 as the others (the rows of a transposed Mat3, whose every
// coefficient is one reduction of a contiguous column: ((t0 + t1) + t2)).
MBK_AVX2 __m256d times(const __m256d& c0, const __m256d& c1, const __m256d& c2, const __m256d& x,
                       bool last_apart) {
  const __m256d t0 = mul(c0, _mm256_permute4x64_pd(x, 0x00));
  const __m256d t1 = mul(c1, _mm256_permute4x64_pd(x, 0x55));
  const __m256d t2 = mul(c2, _mm256_permute4x64_pd(x, 0xAA));
  const __m256d first = add(add(t0, t1), t2);
  return last_apart ? _mm256_blend_pd(first, add(t0, add(t1, t2)), 0x4) : first;
}

// a x b as Eigen's: (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0).
MBK_AVX2 __m256d cross(const __m256d& a, const __m256d& b) {
  const __m256d a_yzx = _mm256_permute4x64_pd(a, 0xC9), b_zxy = _mm256_permute4x64_pd(b, 0xD2);
  const __m256d a_zxy = _mm256_permute4x64_pd(a, 0xD2), b_yzx = _mm256_permute4x64_pd(b, 0xC9);
  return sub(mul(a_yzx, b_zxy), mul(a_zxy, b_yzx));
}

// S0K I_k S0K^T omega_k + m_k (p_k - p_G) x (v_k - v_G) (doc/method.md 9, H_G): the template's
// operations; S0K^T's columns are S0K's rows, transposed in registers.
MBK_AVX2 __m256d body_momentum(const Body& body, const Mat3<double>& s0k, const Vec3<double>& omega,
                               const __m256d& p, const __m256d& v, const __m256d& g,
                               const __m256d& vg) {
  const __m256d c0 = load3(s0k.data()), c1 = load3(s0k.data() + 3), c2 = load3(s0k.data() + 6);
  const __m256d zero = _mm256_setzero_pd();
  const __m256d t0 = _mm256_unpacklo_pd(c0, c1), t1 = _mm256_unpackhi_pd(c0, c1);
  const __m256d t2 = _mm256_unpacklo_pd(c2, zero), t3 = _mm256_unpackhi_pd(c2, zero);
  const __m256d r0 = _mm256_permute2f128_pd(t0, t2, 0x20),
                r1 = _mm256_permute2f128_pd(t1, t3, 0x20);
  const __m256d r2 = _mm256_permute2f128_pd(t0, t2, 0x31);
  const double* in = body.inertia.data();
  const __m256d local = times(r0, r1, r2, load3(omega.data()), false);  // S0K^T omega_k
  const __m256d spin =
      times(c0, c1, c2, times(load3(in), load3(in + 3), load3(in + 6), local, true), true);
  const __m256d orbit = cross(sub(p, g), sub(v, vg));
  return add(spin, mul(_mm256_set1_pd(body.mass), orbit));
}

// system_kinematics<double> at kAcceleration: M and inertias_known, the mass-weighted sums in
// the same pass, then H_G, on vectors.
__attribute__((target("avx2"))) void system_sums_avx2(const Model& model, const Data<double>& data,
                                                      SystemKinematics<double>& out) {
  out = SystemKinematics<double>();
  Vec3<double> p0, v0, a0;
  root_mass_center(model, data, p0, v0, a0);
  const auto p = [&](int k) { return k ? data.mass_center[k].data() : p0.data(); };
  const auto v = [&](int k) { return k ? data.mass_center_velocity[k].data() : v0.data(); };
  const auto a = [&](int k) { return k ? data.mass_center_acceleration[k].data() : a0.data(); };
  bool inertias = true;  // inertias_known
  __m256d g = _mm256_setzero_pd(), momentum = g, acceleration = g;
  for (int k = 0; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    out.mass += body.mass;
    out.has_mass = out.has_mass || body.mass > 0;
    inertias = inertias && !lacks_inertia(body);
    const __m256d m = _mm256_set1_pd(body.mass);
    g = add(g, mul(m, load3(p(k))));
    momentum = add(momentum, mul(m, load3(v(k))));
    acceleration = add(acceleration, mul(m, load3(a(k))));
  }
  out.angular_momentum_known = inertias;
  if (!out.has_mass) return;  // no mass center: every vector zero
  const __m256d total = _mm256_set1_pd(out.mass);
  g = _mm256_div_pd(g, total);
  const __m256d vg = _mm256_div_pd(momentum, total);
  store3(g, out.mass_center);
  store3(momentum, out.linear_momentum);
  store3(vg, out.velocity);
  store3(_mm256_div_pd(acceleration, total), out.acceleration);
  if (!out.angular_momentum_known) return;
  __m256d h = _mm256_setzero_pd();
  for (int k = 0; k <= model.body_count(); ++k)
    h = add(h, body_momentum(model.bodies[k], data.rotation[k], data.omega[k], load3(p(k)),
                             load3(v(k)), g, vg));
  store3(h, out.angular_momentum);
}
#undef MBK_AVX2

}  // namespace system_avx2
}  // namespace
#endif

void system_kinematics(const Model& model, const Data<double>& data, SystemKinematics<double>& out,
                       Level level) {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && level == Level::kAcceleration) {
    assert(sized_for(data, model) && "system_kinematics: Data made for another model");
    return system_avx2::system_sums_avx2(model, data, out);
  }
#endif
  system_kinematics<double>(model, data, out, level);
}

}  // namespace mbk
