// sin_cos over an array (forward_kinematics takes every angle's sine and cosine in one loop,
// kinematics.h) is the one-angle sin_cos bit for bit, and both are within 2 ulp of libm.
#include "mb_kinematics/core/sincos.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Angles in the reduced range, at multiples of pi/2, at its bound, beyond it (libm) and not
// finite; an odd count, so that a vectorized loop has a remainder.
std::vector<double> angles() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> small(-10.0, 10.0), large(-1e6, 1e6);
  std::vector<double> x;
  for (int i = 0; i < 1001; ++i) x.push_back(i % 4 == 3 ? large(rng) : small(rng));
  for (int k = -8; k <= 8; ++k) x.push_back(k * M_PI / 2);
  const double inf = std::numeric_limits<double>::infinity();
  for (double v : {0.0, -0.0, 823549.5, 823549.7, -823549.7, 1e300, inf, -inf,
                   std::numeric_limits<double>::quiet_NaN()})
    x.push_back(v);
  return x;
}

TEST(SinCos, ArrayIsTheOneAngleSinCos) {
  const std::vector<double> x = angles();
  const int n = static_cast<int>(x.size());
  std::vector<double> s(n), c(n);
  mbk::sin_cos(x.data(), n, s.data(), c.data());
  for (int i = 0; i < n; ++i) {
    double si, ci;
    mbk::sin_cos(x[i], si, ci);
    EXPECT_EQ(bits(s[i]), bits(si)) << "sin " << x[i];
    EXPECT_EQ(bits(c[i]), bits(ci)) << "cos " << x[i];
  }
}

TEST(SinCos, WithinTwoUlpOfLibm) {
  for (double x : angles()) {
    if (!std::isfinite(x)) continue;
    double s, c;
    mbk::sin_cos(x, s, c);
    const double ulp_s = std::nextafter(std::abs(std::sin(x)), 2.0) - std::abs(std::sin(x));
    const double ulp_c = std::nextafter(std::abs(std::cos(x)), 2.0) - std::abs(std::cos(x));
    EXPECT_LE(std::abs(s - std::sin(x)), 2 * ulp_s) << "sin " << x;
    EXPECT_LE(std::abs(c - std::cos(x)), 2 * ulp_c) << "cos " << x;
  }
}

}  // namespace
