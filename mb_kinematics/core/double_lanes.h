// N samples' doubles in one scalar, a lane each (N = 4: a 256-bit vector; N = 8: a 512-bit one):
// the batch (offline/batch_kinematics.cc) runs the recursion's templates and the system's on it,
// N samples at once, so that each operation of the code in double is one vector operation for N
// samples (kinematics_lanes.h). Each lane does what the code in double does to its sample,
// operation for operation, with no fused multiply-add (the build's -ffp-contract=off); where Eigen
// would sum three products in another order for a scalar it does not vectorize, the code takes
// detail::product, transpose_product and dot (types.h), which keep double's. So each lane is its
// sample's result in double bit for bit (test/core/kinematics_lanes_test.cc). Arithmetic only: no
// comparison, so the compiler rejects code that would branch on a value.
#pragma once

#include <limits>

#include "mb_kinematics/core/sincos.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

namespace detail {
// GCC's vectors of N doubles (a dependent vector_size is not taken in a template), aligned as a
// double: Eigen's dynamic arrays (a JointState's) give 16 bytes.
typedef double Lanes4 __attribute__((vector_size(32), aligned(8)));
typedef double Lanes8 __attribute__((vector_size(64), aligned(8)));
template <int N>
struct LaneVector;
template <>
struct LaneVector<4> {
  using type = Lanes4;
};
template <>
struct LaneVector<8> {
  using type = Lanes8;
};
}  // namespace detail

template <int N>
struct DoubleLanes {
  using Lanes = typename detail::LaneVector<N>::type;
  Lanes v;

  DoubleLanes() = default;
  DoubleLanes(double x) {  // NOLINT: a constant of the double code, in every lane
    for (int l = 0; l < N; ++l) v[l] = x;
  }
  explicit DoubleLanes(Lanes x) : v(x) {}
  DoubleLanes& operator+=(DoubleLanes o) { return v += o.v, *this; }
  DoubleLanes& operator-=(DoubleLanes o) { return v -= o.v, *this; }
  DoubleLanes& operator*=(DoubleLanes o) { return v *= o.v, *this; }
  DoubleLanes& operator/=(DoubleLanes o) { return v /= o.v, *this; }
  friend DoubleLanes operator+(DoubleLanes a, DoubleLanes b) { return DoubleLanes(a.v + b.v); }
  friend DoubleLanes operator-(DoubleLanes a, DoubleLanes b) { return DoubleLanes(a.v - b.v); }
  friend DoubleLanes operator*(DoubleLanes a, DoubleLanes b) { return DoubleLanes(a.v * b.v); }
  friend DoubleLanes operator/(DoubleLanes a, DoubleLanes b) { return DoubleLanes(a.v / b.v); }
  friend DoubleLanes operator-(DoubleLanes a) { return DoubleLanes(-a.v); }
};
using Double4 = DoubleLanes<4>;
using Double8 = DoubleLanes<8>;

template <int N>
inline constexpr bool kLanes<DoubleLanes<N>> = true;

// sin_cos (sincos.h) of n angles of N samples: the N n doubles' in one loop, bit for bit.
template <int N>
void sin_cos(const DoubleLanes<N>* x, int n, DoubleLanes<N>* s, DoubleLanes<N>* c) {
  static_assert(sizeof(DoubleLanes<N>) == N * sizeof(double), "N packed doubles");
  sin_cos(reinterpret_cast<const double*>(x), N * n, reinterpret_cast<double*>(s),
          reinterpret_cast<double*>(c));
}

}  // namespace mbk

namespace std {
template <int N>
struct numeric_limits<mbk::DoubleLanes<N>> : numeric_limits<double> {};  // double's, each lane
}  // namespace std

namespace Eigen {
template <int N>
struct NumTraits<mbk::DoubleLanes<N>> : GenericNumTraits<mbk::DoubleLanes<N>> {
  typedef mbk::DoubleLanes<N> Real;
  typedef mbk::DoubleLanes<N> NonInteger;
  typedef mbk::DoubleLanes<N> Nested;
  typedef mbk::DoubleLanes<N> Literal;
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
