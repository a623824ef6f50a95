// Four samples' doubles in one scalar, a lane each: the batch (offline/batch_kinematics.cc) runs
// the recursion's templates and the system's on it, four samples at once, so that each operation
// of the code in double is one 256-bit operation for four samples (kinematics_double4.h). Each
// lane does what the code in double does to its sample, operation for operation, with no fused
// multiply-add; where Eigen would sum three products in another order for a scalar it does not
// vectorize, the code takes detail::product, transpose_product and dot (types.h), which keep
// double's. So each lane is its sample's result in double bit for bit
// (test/core/kinematics_double4_test.cc). Arithmetic only: no comparison, so the compiler rejects
// code that would branch on a value.
#pragma once

#include <limits>

#include "mb_kinematics/core/sincos.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

struct Double4 {
  // Aligned as a double: Eigen's dynamic arrays (a JointState's) give 16 bytes.
  typedef double Lanes __attribute__((vector_size(32), aligned(8)));
  Lanes v;

  Double4() = default;
  Double4(double x) : v{x, x, x, x} {}  // NOLINT: a constant of the double code, in every lane
  explicit Double4(Lanes x) : v(x) {}
  Double4& operator+=(Double4 o) { return v += o.v, *this; }
  Double4& operator-=(Double4 o) { return v -= o.v, *this; }
  Double4& operator*=(Double4 o) { return v *= o.v, *this; }
  Double4& operator/=(Double4 o) { return v /= o.v, *this; }
  friend Double4 operator+(Double4 a, Double4 b) { return Double4(a.v + b.v); }
  friend Double4 operator-(Double4 a, Double4 b) { return Double4(a.v - b.v); }
  friend Double4 operator*(Double4 a, Double4 b) { return Double4(a.v * b.v); }
  friend Double4 operator/(Double4 a, Double4 b) { return Double4(a.v / b.v); }
  friend Double4 operator-(Double4 a) { return Double4(-a.v); }
};

template <>
inline constexpr bool kLanes<Double4> = true;

// sin_cos (sincos.h) of n angles of four samples: the 4 n doubles' in one loop, bit for bit.
inline void sin_cos(const Double4* x, int n, Double4* s, Double4* c) {
  static_assert(sizeof(Double4) == 4 * sizeof(double), "Double4: four packed doubles");
  sin_cos(reinterpret_cast<const double*>(x), 4 * n, reinterpret_cast<double*>(s),
          reinterpret_cast<double*>(c));
}

}  // namespace mbk

namespace std {
template <>
struct numeric_limits<mbk::Double4> : numeric_limits<double> {};  // double's, lane by lane
}  // namespace std

namespace Eigen {
template <>
struct NumTraits<mbk::Double4> : GenericNumTraits<mbk::Double4> {
  typedef mbk::Double4 Real;
  typedef mbk::Double4 NonInteger;
  typedef mbk::Double4 Nested;
  typedef mbk::Double4 Literal;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 0,
    ReadCost = 1,
    AddCost = 1,
    MulCost = 1
  };
};
}  // namespace Eigen
