// The sine and cosine of one angle together (one reduction for both), inline, and of an array of
// angles in one loop that vectorizes. For double:
// Cody-Waite reduction by pi/2 (for |x| < 2^19 pi/2), then fdlibm's kernels on [-pi/4, pi/4]
// with the reduction's tail (error below 1 ulp); larger or non-finite angles, and every other
// scalar, take std::sin and std::cos.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace mbk {
namespace detail {

// fdlibm __kernel_sin(x, y): sin(x + y) for |x + y| <= pi/4, y the tail of x.
inline double kernel_sin(double x, double y) {
  constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03,
                   s3 = -1.98412698298579493134e-04, s4 = 2.75573137070700676789e-06,
                   s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
  const double z = x * x, v = z * x;
  const double r = s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)));
  return x - ((z * (0.5 * y - v * r) - y) - v * s1);
}

// fdlibm __kernel_cos(x, y): cos(x + y) for |x + y| <= pi/4.
inline double kernel_cos(double x, double y) {
  constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03,
                   c3 = 2.48015872894767294178e-05, c4 = -2.75573143513906633035e-07,
                   c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;
  const double z = x * x, w = z * z;
  const double r = z * (c1 + z * (c2 + z * c3)) + w * w * (c4 + z * (c5 + z * c6));
  const double hz = 0.5 * z, u = 1.0 - hz;
  return u + (((1.0 - u) - hz) + (z * r - x * y));
}

// 2^19 pi/2: below it, |n| < 2^19 in sin_cos_reduced, so n * pio2_1 is exact.
constexpr double kReducedBound = 823549.6;

// sin and cos of |x| < kReducedBound without a branch (a loop over angles vectorizes; other x
// give some number). x = n pi/2
// + (y0 + y1): pi/2 = pio2_1 + pio2_2 + pio2_2t, the first two of 33 bits (fdlibm
// __ieee754_rem_pio2, its second reduction step); y0 + y1 within 1e-20 of the remainder.
inline void sin_cos_reduced(double x, double& s, double& c) {
  constexpr double invpio2 = 6.36619772367581382433e-01, pio2_1 = 1.57079632673412561417e+00,
                   pio2_2 = 6.07710050630396597660e-11, pio2_2t = 2.02226624879595063154e-21;
  constexpr double round = 0x1.8p52;  // adding and taking it away rounds to an integer
  const double t = x * invpio2 + round, n = t - round;
  const double r1 = x - n * pio2_1;  // exact (Sterbenz)
  double w = n * pio2_2;
  const double r = r1 - w;
  w = n * pio2_2t - ((r1 - r) - w);
  const double y0 = r - w, y1 = (r - y0) - w;
  const double ks = kernel_sin(y0, y1), kc = kernel_cos(y0, y1);
  std::uint64_t bits;  // t's last bits hold n (|n| < 2^51): its quadrant, for any x without UB
  std::memcpy(&bits, &t, sizeof bits);
  const std::uint32_t quadrant = static_cast<std::uint32_t>(bits) & 3;
  const double ss = quadrant & 1 ? kc : ks, cc = quadrant & 1 ? ks : kc;
  s = quadrant & 2 ? -ss : ss;
  c = (quadrant + 1) & 2 ? -cc : cc;
}

}  // namespace detail

template <typename S>
void sin_cos(S x, S& s, S& c) {
  using std::cos;
  using std::sin;
  if constexpr (std::is_same_v<S, double>) {
    if (std::abs(x) < detail::kReducedBound) return detail::sin_cos_reduced(x, s, c);
  }
  s = sin(x);
  c = cos(x);
}

// sin_cos of x[0..n-1] into s and c (arrays apart from x), bit for bit: for double, one loop
// without branches over every angle (the compiler vectorizes it), then libm for the rare large
// or non-finite ones, looked for one by one only when a vectorized pass finds some (an int
// flag: GCC vectorizes the OR of ints, not of bools).
template <typename S>
void sin_cos(const S* x, int n, S* s, S* c) {
  if constexpr (std::is_same_v<S, double>) {
    for (int i = 0; i < n; ++i) detail::sin_cos_reduced(x[i], s[i], c[i]);
    int large = 0;
    for (int i = 0; i < n; ++i) large |= !(std::abs(x[i]) < detail::kReducedBound);
    if (!large) return;
    for (int i = 0; i < n; ++i)
      if (!(std::abs(x[i]) < detail::kReducedBound)) s[i] = std::sin(x[i]), c[i] = std::cos(x[i]);
  } else {
    for (int i = 0; i < n; ++i) sin_cos(x[i], s[i], c[i]);
  }
}

}  // namespace mbk
