// The 12 orders of three successive rotations about body-fixed (intrinsic) axes, for the angles of
// ball and free joints: SJK = C_k R_a1(alpha) R_a2(beta) R_a3(gamma), a1 != a2 != a3. Six are
// Tait-Bryan (three different axes, the chapter's 1-2-3 = XYZ among them) and six proper Euler
// (first axis repeated: XYX, ...). A BVH channel line "Zrotation Xrotation Yrotation" is ZXY.
#pragma once

#include <array>
#include <string>
#include <type_traits>

#include "mb_kinematics/core/types.h"

namespace mbk {

enum class EulerOrder {
  kXYZ,  // 1-2-3, the chapter's (eq. 4.4.9-4.4.12)
  kXZY,
  kYXZ,
  kYZX,
  kZXY,
  kZYX,
  kXYX,
  kXZX,
  kYXY,
  kYZY,
  kZXZ,
  kZYZ,
  kLast = kZYZ,  // keep equal to the last order
};

// One row of the table below: an order's axes a1, a2, a3 (0 = x, 1 = y, 2 = z), `third` the axis
// neither a1 nor a2 and sigma the sign of e_a1 x e_a2 = sigma e_third (+1 for the cyclic pairs
// xy, yz, zx), and whether it is proper Euler (a3 == a1) or Tait-Bryan. The recursion's kernels
// turn about these axes (fast_kernels.h) and EulerMap below is built from the same row.
struct EulerTurns {
  int a1, a2, a3, third, sigma;
  bool proper;  // a3 == a1
};

namespace detail {

constexpr EulerTurns make_euler_turns(int a1, int a2, int a3) {
  return EulerTurns{a1, a2, a3, 3 - a1 - a2, (a2 - a1 + 3) % 3 == 1 ? 1 : -1, a3 == a1};
}

}  // namespace detail

// The 12 orders, in EulerOrder order: the one table of the orders' axes and signs.
inline constexpr std::array<EulerTurns, 12> kEulerOrders{
    detail::make_euler_turns(0, 1, 2), detail::make_euler_turns(0, 2, 1),
    detail::make_euler_turns(1, 0, 2), detail::make_euler_turns(1, 2, 0),
    detail::make_euler_turns(2, 0, 1), detail::make_euler_turns(2, 1, 0),
    detail::make_euler_turns(0, 1, 0), detail::make_euler_turns(0, 2, 0),
    detail::make_euler_turns(1, 0, 1), detail::make_euler_turns(1, 2, 1),
    detail::make_euler_turns(2, 0, 2), detail::make_euler_turns(2, 1, 2)};

constexpr EulerTurns euler_turns(EulerOrder order) {
  return kEulerOrders[static_cast<size_t>(order)];
}

// The axes of the three rotations in order, 0 = x, 1 = y, 2 = z.
std::array<int, 3> euler_axes(EulerOrder order);
// True for the six Tait-Bryan orders (three different axes).
bool is_tait_bryan(EulerOrder order);
// "XYZ", "ZXY", ... (upper case).
std::string to_string(EulerOrder order);
// Reads "XYZ"/"xyz" or the digits "123", "313", ... (1 = x, 2 = y, 3 = z). Throws
// std::invalid_argument naming the text for anything else (two equal successive axes, other
// letters, other lengths).
EulerOrder euler_order_from_string(const std::string& text);
// The order whose axes are `axes` (0 = x, 1 = y, 2 = z); std::invalid_argument if two successive
// axes are equal or an axis is out of range.
EulerOrder euler_order_from_axes(const std::array<int, 3>& axes);

// Every order is the chapter's 1-2-3 rotation between two constant signed axis permutations
// (each built from the order's row of kEulerOrders; joint_motion and base_joint use them):
//   R_a1(alpha) R_a2(beta) R_a3(gamma) = P R_123(alpha, beta + shift, sign * gamma) Q.
// Proof. For a rotation P, P R_u(t) P^T = R_{P u}(t). Take P with columns e_a1, e_a2,
// e_a1 x e_a2 (a proper rotation): P R_x(t) P^T = R_a1(t), P R_y(t) P^T = R_a2(t).
// - Tait-Bryan (a3 != a1): e_a1 x e_a2 = sign e_a3, sign = sigma: +1 for the cyclic orders XYZ,
//   YZX, ZXY and -1 for the others, so P R_z(sign t) P^T = R_{sign e_a3}(sign t) = R_a3(t). Then
//   R_a1 R_a2 R_a3 = P R_x(alpha) R_y(beta) R_z(sign gamma) P^T: shift 0, Q = P^T.
// - Proper Euler (a3 = a1): R_y(pi/2) carries e_z to e_x, so R_x(t) = R_y(pi/2) R_z(t) R_y(-pi/2)
//   and R_a1(gamma) = P R_y(pi/2) R_z(gamma) R_y(-pi/2) P^T; R_y(beta) R_y(pi/2) =
//   R_y(beta + pi/2): shift pi/2, sign +1, Q = R_y(-pi/2) P^T.
// P and Q being constant, the relative angular velocity (in Bj) is P times the 1-2-3 one at the
// shifted angles: [w] = R' R^T = P (R_123' R_123^T) P^T, and its columns are P [e1, A e2,
// sign A B e3] (eq. 4.4.13-4.4.16); the gimbal lock is cos(beta + shift) = 0: beta = +-90 deg
// (Tait-Bryan), beta = 0 or 180 deg (proper Euler). The shift is exact: cos(beta + pi/2) =
// -sin beta, sin(beta + pi/2) = cos beta. euler_order_test checks the identity for all 12.
struct SignedPermutation {  // column j is sign[j] times the unit vector e_{index[j]}
  std::array<int, 3> index;
  std::array<int, 3> sign;
  Mat3<double> matrix() const;
  template <typename S>
  Vec3<S> times(const Vec3<S>& v) const {  // P v = sum_j v_j sign_j e_{index_j}
    Vec3<S> out;
    for (int j = 0; j < 3; ++j) out[index[j]] = S(sign[j]) * v[j];
    return out;
  }
  template <typename S>
  Vec3<S> transpose_times(const Vec3<S>& v) const {  // row j of P^T is column j of P
    return Vec3<S>(S(sign[0]) * v[index[0]], S(sign[1]) * v[index[1]], S(sign[2]) * v[index[2]]);
  }
};

struct EulerMap {
  SignedPermutation p, q;
  bool shifted;    // proper Euler: beta + pi/2 (cos -> -sin beta, sin -> cos beta)
  int gamma_sign;  // -1 for the non-cyclic Tait-Bryan orders
};

namespace detail {

constexpr SignedPermutation product(const SignedPermutation& a, const SignedPermutation& b) {
  SignedPermutation ab{};  // column j of A B = sign_b[j] A e_{index_b[j]}
  for (int j = 0; j < 3; ++j) {
    ab.index[j] = a.index[b.index[j]];
    ab.sign[j] = a.sign[b.index[j]] * b.sign[j];
  }
  return ab;
}

constexpr SignedPermutation transpose(const SignedPermutation& a) {
  SignedPermutation t{};  // column index[j] of A^T is sign[j] e_j
  for (int j = 0; j < 3; ++j) {
    t.index[a.index[j]] = j;
    t.sign[a.index[j]] = a.sign[j];
  }
  return t;
}

constexpr EulerMap make_euler_map(const EulerTurns& o) {
  const SignedPermutation p{{o.a1, o.a2, o.third}, {1, 1, o.sigma}};
  const SignedPermutation turn{{2, 1, 0}, {1, 1, -1}};  // R_y(-pi/2)
  return EulerMap{p, o.proper ? product(turn, transpose(p)) : transpose(p), o.proper,
                  o.proper ? 1 : o.sigma};
}

}  // namespace detail

// The map of each order, in EulerOrder order.
inline constexpr std::array<EulerMap, 12> kEulerMaps{
    detail::make_euler_map(kEulerOrders[0]),  detail::make_euler_map(kEulerOrders[1]),
    detail::make_euler_map(kEulerOrders[2]),  detail::make_euler_map(kEulerOrders[3]),
    detail::make_euler_map(kEulerOrders[4]),  detail::make_euler_map(kEulerOrders[5]),
    detail::make_euler_map(kEulerOrders[6]),  detail::make_euler_map(kEulerOrders[7]),
    detail::make_euler_map(kEulerOrders[8]),  detail::make_euler_map(kEulerOrders[9]),
    detail::make_euler_map(kEulerOrders[10]), detail::make_euler_map(kEulerOrders[11])};

inline const EulerMap& euler_map(EulerOrder order) {
  return kEulerMaps[static_cast<size_t>(order)];
}

// f(std::integral_constant<EulerOrder, order>{}): a kernel templated on the order, so its maps
// are constants (one instance per order, as Pinocchio instantiates per joint type).
template <typename F>
void with_euler_order(EulerOrder order, F&& f) {
  using O = EulerOrder;
  switch (order) {
    case O::kXYZ:
      return f(std::integral_constant<O, O::kXYZ>{});
    case O::kXZY:
      return f(std::integral_constant<O, O::kXZY>{});
    case O::kYXZ:
      return f(std::integral_constant<O, O::kYXZ>{});
    case O::kYZX:
      return f(std::integral_constant<O, O::kYZX>{});
    case O::kZXY:
      return f(std::integral_constant<O, O::kZXY>{});
    case O::kZYX:
      return f(std::integral_constant<O, O::kZYX>{});
    case O::kXYX:
      return f(std::integral_constant<O, O::kXYX>{});
    case O::kXZX:
      return f(std::integral_constant<O, O::kXZX>{});
    case O::kYXY:
      return f(std::integral_constant<O, O::kYXY>{});
    case O::kYZY:
      return f(std::integral_constant<O, O::kYZY>{});
    case O::kZXZ:
      return f(std::integral_constant<O, O::kZXZ>{});
    case O::kZYZ:
      return f(std::integral_constant<O, O::kZYZ>{});
  }
  __builtin_unreachable();  // every EulerOrder is a case: no range check per body
}

}  // namespace mbk
