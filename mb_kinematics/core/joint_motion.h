// What a joint contributes, per update: SJK, s_k, and the columns that map its generalized
// speeds to the relative angular velocity w_k and translation rate s_k' (doc/method.md 2, 4, 5).
#pragma once

#include <cmath>

#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/core/sincos.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

constexpr int kMaxJointSpeeds = 7;

// Every speed of a joint is either a translation rate or a rotation rate: speeds c <
// linear_speeds move O_k along linear[c], the others turn Bk about angular[c]. All vectors in Bj
// components: s_k' = sum_{c < linear_speeds} linear[c] y_c (constant in Bj), and
// w_k = sum_{c >= linear_speeds} angular[c] y_c, w_k' = sum (angular[c] y_c' + angular_dot[c] y_c).
template <typename S>
struct JointMotion {
  Mat3<S> rotation;     // SJK = C_k R_motion
  Vec3<S> translation;  // s_k
  int linear_speeds = 0;
  int speeds = 0;
  Vec3<S> linear[kMaxJointSpeeds];
  Vec3<S> angular[kMaxJointSpeeds];
  Vec3<S> angular_dot[kMaxJointSpeeds];
};

namespace detail {

// A(alpha) B(beta) C(gamma) multiplied out, from the sines and cosines.
template <typename S>
Mat3<S> rotation_123(S ca, S sa, S cb, S sb, S cg, S sg) {
  Mat3<S> r;
  r << cb * cg, -cb * sg, sb,                                    //
      sa * sb * cg + ca * sg, ca * cg - sa * sb * sg, -sa * cb,  //
      sa * sg - ca * sb * cg, ca * sb * sg + sa * cg, ca * cb;
  return r;
}

}  // namespace detail

// 1-2-3 rotation A(alpha) B(beta) C(gamma) (eq. 4.4.9-4.4.12, with the erratum of doc/method.md 7).
template <typename S>
Mat3<S> rotation_123(S alpha, S beta, S gamma) {
  using std::cos;
  using std::sin;
  return detail::rotation_123(cos(alpha), sin(alpha), cos(beta), sin(beta), cos(gamma), sin(gamma));
}

// Rotation of Euler parameters e = (e1, e2, e3, e4), e4 scalar, divided by |e|^2 so that an
// unnormalized e gives the rotation of e / |e|: (e4^2 - |v|^2) I + 2 v v^T + 2 e4 [v]x, entry by
// entry without the zero terms.
template <typename S>
Mat3<S> rotation_euler(const S* e) {
  const Vec3<S> v(e[0], e[1], e[2]), w = S(2) * v;  // w = 2 v
  const S n2 = detail::squared_norm(v) + e[3] * e[3];
  const S d = e[3] * e[3] - detail::squared_norm(v), f = S(2) * e[3];
  Mat3<S> r;
  r << d + w.x() * v.x(), w.x() * v.y() - f * v.z(), w.x() * v.z() + f * v.y(),  //
      w.y() * v.x() + f * v.z(), d + w.y() * v.y(), w.y() * v.z() - f * v.x(),   //
      w.z() * v.x() - f * v.y(), w.z() * v.y() + f * v.x(), d + w.z() * v.z();
  return r / n2;
}

// Rotation by angle theta about a unit axis (Rodrigues): c I + s [a]x + (1 - c) a a^T.
template <typename S>
Mat3<S> rotation_axis(const Vec3<S>& axis, S theta) {
  S c, s;
  sin_cos(theta, s, c);
  Mat3<S> r = (S(1) - c) * axis * axis.transpose() + s * skew(axis);
  r.diagonal().array() += c;
  return r;
}

namespace detail {

// 1-2-3 angle columns [e1, A e2, A B e3] and their time derivatives (eq. 4.4.13-4.4.16, 4.5),
// from the sines and cosines of alpha and beta.
template <typename S>
void angles_123_columns(S ca, S sa, S cb, S sb, const S* qd, Vec3<S>* angular,
                        Vec3<S>* angular_dot) {
  angular[0] = Vec3<S>(S(1), S(0), S(0));
  angular[1] = Vec3<S>(S(0), ca, sa);
  angular[2] = Vec3<S>(sb, -sa * cb, ca * cb);
  angular_dot[0].setZero();
  angular_dot[1] = qd[0] * Vec3<S>(S(0), -sa, ca);
  angular_dot[2] =
      qd[0] * Vec3<S>(S(0), -ca * cb, -sa * cb) + qd[1] * Vec3<S>(cb, sa * sb, -ca * sb);
}

// Ball and free joints' angles alpha, beta, gamma in the order O (euler_order.h): the 1-2-3
// rotation and columns at (alpha, beta + shift, sign gamma), carried by the order's P and Q:
// SJK = P R_123 Q, columns P [e1, A e2, sign A B e3] and their rates. c, s: the angles' cosines
// and sines; qd: nullptr for the rotation alone.
template <EulerOrder O, typename S>
Mat3<S> ordered_angles_motion(const S* c, const S* s, const S* qd, Vec3<S>* angular,
                              Vec3<S>* angular_dot) {
  constexpr EulerMap map = kEulerMaps[static_cast<size_t>(O)];
  const S cb = map.shifted ? -s[1] : c[1], sb = map.shifted ? c[1] : s[1];  // of beta + shift
  if (qd) {
    angles_123_columns(c[0], s[0], cb, sb, qd, angular, angular_dot);
    angular[2] *= S(map.gamma_sign);  // the rate of sign * gamma is sign * gamma'
    angular_dot[2] *= S(map.gamma_sign);
    for (int i = 0; i < 3; ++i) {
      angular[i] = map.p.times(angular[i]);
      angular_dot[i] = map.p.times(angular_dot[i]);
    }
  }
  const Mat3<S> r = rotation_123(c[0], s[0], cb, sb, c[2], S(map.gamma_sign) * s[2]);
  Mat3<S> out;  // P r Q, column j of r Q = sign_j r e_{index_j}
  for (int j = 0; j < 3; ++j)
    out.col(j) = map.p.times(Vec3<S>(S(map.q.sign[j]) * r.col(map.q.index[j])));
  return out;
}

// The same in any order, each order's instance (with_euler_order).
template <typename S>
Mat3<S> angles_motion(EulerOrder order, const S* q, const S* qd, Vec3<S>* angular,
                      Vec3<S>* angular_dot) {
  S c[3], s[3];
  for (int i = 0; i < 3; ++i) sin_cos(q[i], s[i], c[i]);
  if (order == EulerOrder::kXYZ) {  // P = Q = I
    if (qd) angles_123_columns(c[0], s[0], c[1], s[1], qd, angular, angular_dot);
    return rotation_123(c[0], s[0], c[1], s[1], c[2], s[2]);
  }
  Mat3<S> out;
  with_euler_order(order, [&](auto o) {
    out = ordered_angles_motion<decltype(o)::value>(c, s, qd, angular, angular_dot);
  });
  return out;
}

// Euler-parameter columns: w = 2 (e4 e' - e4' e + e x e') / |e|^2, with coordinate-derivative
// speeds (e1'..e4'), or the identity with angular velocity speeds.
template <typename S>
int euler_columns(const S* e, const S* ed, SpeedKind speeds, Vec3<S>* angular,
                  Vec3<S>* angular_dot) {
  if (speeds == SpeedKind::kAngularVelocity) {
    for (int i = 0; i < 3; ++i) {
      angular[i] = Vec3<S>::Unit(i);
      if (ed) angular_dot[i].setZero();
    }
    return 3;
  }
  const Vec3<S> v(e[0], e[1], e[2]);
  const S n2 = detail::squared_norm(v) + e[3] * e[3];
  for (int i = 0; i < 3; ++i)
    angular[i] = S(2) / n2 * (e[3] * Vec3<S>::Unit(i) + v.cross(Vec3<S>::Unit(i)));
  angular[3] = S(-2) / n2 * v;
  if (!ed) return 4;
  const Vec3<S> vd(ed[0], ed[1], ed[2]);
  const S n2_dot = S(2) * (detail::dot(v, vd) + e[3] * ed[3]);
  for (int i = 0; i < 3; ++i)
    angular_dot[i] = S(2) / n2 * (ed[3] * Vec3<S>::Unit(i) + vd.cross(Vec3<S>::Unit(i))) -
                     n2_dot / n2 * angular[i];
  angular_dot[3] = S(-2) / n2 * vd - n2_dot / n2 * angular[3];
  return 4;
}

// Unit vectors u1, u2 with (u1, u2, normal) right-handed; x and y for the z axis.
template <typename S>
void plane_basis(const Vec3<S>& normal, Vec3<S>& u1, Vec3<S>& u2) {
  using std::abs;
  const Vec3<S> seed = abs(normal.z()) > S(0.9) ? Vec3<S>::UnitX() : Vec3<S>::UnitZ();
  u2 = normal.cross(seed).normalized();
  u1 = u2.cross(normal);
}

// Euler parameters e = (v, e4), in the joint frame: w = 2 (e4 v' - e4' v + v x v') / |e|^2 and
// its derivative w' = 2 (e4 v'' - e4'' v + v x v'') / |e|^2 - (|e|^2)' / |e|^2 w (the v' terms
// cancel), with coordinate-derivative speeds; w = y with angular velocity speeds. yd: nullptr
// when w' is not wanted.
template <typename S>
void euler_rates(const S* e, const S* y, const S* yd, SpeedKind speeds, Vec3<S>& w, Vec3<S>& wd) {
  if (speeds == SpeedKind::kAngularVelocity) {
    w = Vec3<S>(y[0], y[1], y[2]);
    if (yd) wd = Vec3<S>(yd[0], yd[1], yd[2]);
    return;
  }
  const Vec3<S> v(e[0], e[1], e[2]), vd(y[0], y[1], y[2]);
  const S n2 = detail::squared_norm(v) + e[3] * e[3];
  w = S(2) / n2 * (e[3] * vd - y[3] * v + v.cross(vd));
  if (!yd) return;
  const Vec3<S> vdd(yd[0], yd[1], yd[2]);
  const S n2_dot = S(2) * (detail::dot(v, vd) + e[3] * y[3]);
  wd = S(2) / n2 * (e[3] * vdd - yd[3] * v + v.cross(vdd)) - n2_dot / n2 * w;
}

}  // namespace detail

// Fills `out` for one joint. q: the joint's coordinates; qd: its speeds, or nullptr when only
// the pose is wanted (then the columns are left unset).
template <typename S>
void joint_motion(const Joint& joint, SpeedKind speeds, const S* q, const S* qd,
                  JointMotion<S>& out) {
  const Vec3<S> axis = joint.axis.cast<S>();
  Mat3<S> motion = Mat3<S>::Identity();
  Vec3<S> s = Vec3<S>::Zero();
  int t = 0, n = 0;  // linear speeds, all speeds
  switch (joint.type) {
    case JointType::kFixed:
      break;
    case JointType::kRevolute:
      motion = rotation_axis(axis, q[0]);
      n = 1;
      out.angular[0] = axis;
      out.angular_dot[0].setZero();
      break;
    case JointType::kPrismatic:
      s = axis * q[0];
      t = n = 1;
      out.linear[0] = axis;
      break;
    case JointType::kBall123:
    case JointType::kFree123:
      t = joint.type == JointType::kFree123 ? 3 : 0;
      motion = detail::angles_motion(joint.euler_order, q + t, qd ? qd + t : nullptr,
                                     out.angular + t, out.angular_dot + t);
      n = t + 3;
      break;
    case JointType::kBallEuler:
    case JointType::kFreeEuler:
      t = joint.type == JointType::kFreeEuler ? 3 : 0;
      motion = rotation_euler(q + t);
      n = t + detail::euler_columns(q + t, qd ? qd + t : nullptr, speeds, out.angular + t,
                                    out.angular_dot + t);
      break;
    case JointType::kPlanar: {
      Vec3<S> u1, u2;
      detail::plane_basis(axis, u1, u2);
      s = q[0] * u1 + q[1] * u2;
      motion = rotation_axis(axis, q[2]);
      t = 2;
      n = 3;
      out.linear[0] = u1;
      out.linear[1] = u2;
      out.angular[2] = axis;
      out.angular_dot[2].setZero();
      break;
    }
    case JointType::kUniversal: {  // A(alpha) B(beta): the 1-2-3 angles without gamma
      S ca, sa, cb, sb;
      sin_cos(q[0], sa, ca);
      sin_cos(q[1], sb, cb);
      motion = detail::rotation_123(ca, sa, cb, sb, S(1), S(0));
      if (qd) detail::angles_123_columns(ca, sa, cb, sb, qd, out.angular, out.angular_dot);
      n = 2;  // columns e1, A e2 (eq. 4.4.13-4.4.16)
      break;
    }
  }
  if (t == 3) {  // free joints: translations along the joint frame's axes
    s = Vec3<S>(q[0], q[1], q[2]);
    for (int i = 0; i < 3; ++i) out.linear[i] = Vec3<S>::Unit(i);
  }
  out.linear_speeds = t;
  out.speeds = n;
  if (joint.rotation == Mat3<double>::Identity()) {  // no offset rotation: joint frame = Bj
    out.rotation = motion;
    out.translation = s;
    return;
  }
  const Mat3<S> c = joint.rotation.cast<S>();
  out.rotation = c * motion;
  out.translation = c * s;
  if (!qd) return;
  for (int i = 0; i < t; ++i) out.linear[i] = c * out.linear[i];  // joint frame to Bj
  for (int i = t; i < n; ++i) {
    out.angular[i] = c * out.angular[i];
    out.angular_dot[i] = c * out.angular_dot[i];
  }
}

// SJK of `joint` as a unit quaternion, without the matrix (the tf output's form): C_k's, given
// as `offset` (its quaternion, made once), times the motion's. q: the joint's coordinates.
template <typename S>
Eigen::Quaternion<S> joint_quaternion(const Joint& joint, const Eigen::Quaternion<S>& offset,
                                      const S* q) {
  const Vec3<S> axis = joint.axis.cast<S>();
  const auto turn = [](const Vec3<S>& a, S angle) {  // angle about the unit vector a
    S s, c;
    sin_cos(angle / S(2), s, c);
    return Eigen::Quaternion<S>(c, s * a.x(), s * a.y(), s * a.z());
  };
  switch (joint.type) {
    case JointType::kFixed:
    case JointType::kPrismatic:
      return offset;
    case JointType::kRevolute:
      return offset * turn(axis, q[0]);
    case JointType::kPlanar:
      return offset * turn(axis, q[2]);
    case JointType::kUniversal:
      return offset * turn(Vec3<S>::UnitX(), q[0]) * turn(Vec3<S>::UnitY(), q[1]);
    case JointType::kBall123:
    case JointType::kFree123: {
      const S* a = joint.type == JointType::kFree123 ? q + 3 : q;  // R_a1(alpha) R_a2(beta) ...
      const std::array<int, 3> axes = euler_axes(joint.euler_order);
      return offset * turn(Vec3<S>::Unit(axes[0]), a[0]) * turn(Vec3<S>::Unit(axes[1]), a[1]) *
             turn(Vec3<S>::Unit(axes[2]), a[2]);
    }
    case JointType::kBallEuler:
    case JointType::kFreeEuler: {
      const S* e = joint.type == JointType::kFreeEuler ? q + 3 : q;  // e4: the scalar part
      return offset * Eigen::Quaternion<S>(e[3], e[0], e[1], e[2]).normalized();
    }
  }
  return offset;
}

}  // namespace mbk
