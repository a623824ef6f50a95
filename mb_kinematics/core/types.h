// Small fixed-size Eigen types used across the core, templated on the scalar.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <type_traits>

namespace mbk {

template <typename S>
using Vec3 = Eigen::Matrix<S, 3, 1>;
template <typename S>
using Mat3 = Eigen::Matrix<S, 3, 3>;
// Whether S holds several samples, a lane each (double_lanes.h): the recursion's templates run on
// it, not the generic kernel, whose joint_motion branches on values.
template <typename S>
inline constexpr bool kLanes = false;

template <typename S>
using VecX = Eigen::Matrix<S, Eigen::Dynamic, 1>;

// Skew-symmetric matrix [v]x with [v]x u = v x u.
template <typename S>
Mat3<S> skew(const Vec3<S>& v) {
  Mat3<S> m;
  m << S(0), -v.z(), v.y(), v.z(), S(0), -v.x(), -v.y(), v.x(), S(0);
  return m;
}

namespace detail {

// m itself if it is a matrix, else m evaluated: a matrix without a copy.
template <typename M>
decltype(auto) plain(const M& m) {
  if constexpr (std::is_base_of_v<Eigen::PlainObjectBase<M>, M>)
    return (m);
  else
    return m.eval();
}

// a b (a 3x3, b 3x3 or 3x1) and a^T b, for every product of the recursion and the system's:
// Eigen's. For samples in lanes (kLanes, double_lanes.h), each lane as Eigen computes it in double
// on SSE2's packets of two (the portable build's; kinematics_lanes.h): a b sums rows 0 and 1 of
// each column on a packet, (a_i0 b_0j + a_i1 b_1j) + a_i2 b_2j, and row 2 alone, a_20 b_0j +
// (a_21 b_1j + a_22 b_2j); a^T b sums every row as rows 0 and 1. Eigen's own code for a scalar
// it does not vectorize sums every row as row 2 of a b (test/core/kinematics_lanes_test.cc).
template <bool kTransposed, typename S, typename A, typename B>
auto lanes_product(const A& a, const B& b) {
  const auto& x = plain(a);
  const auto& y = plain(b);
  Eigen::Matrix<S, 3, B::ColsAtCompileTime> r;
  for (int j = 0; j < y.cols(); ++j)
    for (int i = 0; i < 3; ++i) {
      const S t0 = (kTransposed ? x(0, i) : x(i, 0)) * y(0, j);
      const S t1 = (kTransposed ? x(1, i) : x(i, 1)) * y(1, j);
      const S t2 = (kTransposed ? x(2, i) : x(i, 2)) * y(2, j);
      r(i, j) = kTransposed || i < 2 ? (t0 + t1) + t2 : t0 + (t1 + t2);
    }
  return r;
}

template <typename S, typename A, typename B>
auto product(const A& a, const B& b) {
  if constexpr (kLanes<S>)
    return lanes_product<false, S>(a, b);
  else
    return a * b;
}

template <typename S, typename A, typename B>
auto transpose_product(const A& a, const B& b) {
  if constexpr (kLanes<S>)
    return lanes_product<true, S>(a, b);
  else
    return a.transpose() * b;
}

// a . b and |a|^2 of three-vectors: Eigen's. For samples in lanes, each lane as Eigen sums them
// in double, vectorized: (a_0 b_0 + a_1 b_1) + a_2 b_2.
template <typename S>
S dot(const Vec3<S>& a, const Vec3<S>& b) {
  if constexpr (!kLanes<S>)
    return a.dot(b);
  else
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

template <typename S>
S squared_norm(const Vec3<S>& a) {
  if constexpr (!kLanes<S>)
    return a.squaredNorm();
  else
    return dot(a, a);
}

}  // namespace detail

}  // namespace mbk
