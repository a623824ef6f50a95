#include "mb_kinematics/core/base_joint.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "mb_kinematics/core/joint_motion.h"

namespace mbk {

namespace {

void take_mass_properties(const Body& from, Body& to) {
  to.mass = from.mass;
  to.mass_center = from.mass_center;
  to.inertia = from.inertia;
  to.has_inertia = from.has_inertia;
}

}  // namespace

bool has_floating_root(const Model& model) {
  if (model.body_count() < 1 || model.bodies[1].lower != 0) return false;
  const JointType type = model.bodies[1].joint.type;
  if (type != JointType::kFree123 && type != JointType::kFreeEuler) return false;
  for (int k = 2; k <= model.body_count(); ++k)
    if (model.bodies[k].lower == 0) return false;
  return true;
}

Model with_floating_base(const Model& model, const std::string& frame, const std::string& joint) {
  Model out;
  out.frame = frame;
  out.speeds = model.speeds;
  out.warnings = model.warnings;
  out.bodies.resize(2);
  out.bodies[1].name = model.frame;
  out.bodies[1].joint.name = joint;
  out.bodies[1].joint.type = JointType::kFreeEuler;
  take_mass_properties(model.bodies[0], out.bodies[1]);  // the root link moves with the base
  for (int k = 1; k <= model.body_count(); ++k) {
    Body b = model.bodies[k];
    b.lower += 1;  // R's children now hang from the base
    out.bodies.push_back(b);
  }
  const int shift = coordinate_count(JointType::kFreeEuler);
  for (Mimic m : model.mimics) {
    m.coordinate += shift;
    m.source += shift;
    out.mimics.push_back(m);
  }
  finalize_model(out);
  return out;
}

Model without_root_body(const Model& model) {
  Model out;
  out.frame = model.bodies[1].name;
  out.speeds = model.speeds;
  out.warnings = model.warnings;
  out.bodies.resize(1);
  take_mass_properties(model.bodies[1], out.bodies[0]);  // body 1's link is now fixed in R
  for (int k = 2; k <= model.body_count(); ++k) {
    Body b = model.bodies[k];
    b.lower = std::max(b.lower - 1, 0);  // body 1's children now hang from R
    out.bodies.push_back(b);
  }
  const int shift = coordinate_count(model.bodies[1].joint.type);
  for (Mimic m : model.mimics) {
    m.coordinate -= shift;
    m.source -= shift;
    out.mimics.push_back(m);
  }
  finalize_model(out);
  return out;
}

namespace {

// Euler parameters of `r` and their derivatives for the angular velocity w and acceleration
// alpha in the joint frame: e' = (e4 w + w x e) / 2, e4' = -w.e / 2 (so that
// w = 2 (e4 e' - e4' e + e x e'), joint_motion.h), and their time derivatives.
void euler_coordinates(const Mat3<double>& r, const Vec3<double>& w, const Vec3<double>& alpha,
                       double* q, double* qd, double* qdd) {
  const Eigen::Quaterniond e(r);
  const Vec3<double> v = e.vec();
  const Vec3<double> vd = 0.5 * (e.w() * w + w.cross(v));
  const double wd = -0.5 * w.dot(v);
  for (int i = 0; i < 3; ++i) {
    q[i] = v[i];
    qd[i] = vd[i];
  }
  q[3] = e.w();
  qd[3] = wd;
  if (!qdd) return;
  const Vec3<double> vdd = 0.5 * (e.w() * alpha + alpha.cross(v) + wd * w + w.cross(vd));
  for (int i = 0; i < 3; ++i) qdd[i] = vdd[i];
  qdd[3] = -0.5 * (alpha.dot(v) + w.dot(vd));
}

// 1-2-3 angles of r = A(a) B(b) C(g) and their derivatives: w = M q', w' = M q'' + M' q', with
// M = [e1, A e2, A B e3] (eq. 4.4.13-4.4.16).
std::string angles_123_coordinates(const Mat3<double>& r, const Vec3<double>& w,
                                   const Vec3<double>& alpha, double* q, double* qd, double* qdd) {
  const double b = std::asin(std::clamp(r(0, 2), -1.0, 1.0));
  if (std::abs(std::cos(b)) < 1e-9) return "at gimbal lock";
  q[0] = std::atan2(-r(1, 2), r(2, 2));
  q[1] = b;
  q[2] = std::atan2(-r(0, 1), r(0, 0));
  const double ca = std::cos(q[0]), sa = std::sin(q[0]), cb = std::cos(b), sb = std::sin(b);
  Vec3<double> columns[3], columns_dot[3];
  const double zero[3] = {0, 0, 0};
  detail::angles_123_columns(ca, sa, cb, sb, zero, columns, columns_dot);
  Mat3<double> m;
  for (int i = 0; i < 3; ++i) m.col(i) = columns[i];
  const Eigen::PartialPivLU<Mat3<double>> lu(m);
  const Vec3<double> rates = lu.solve(w);
  for (int i = 0; i < 3; ++i) qd[i] = rates[i];
  if (!qdd) return "";
  detail::angles_123_columns(ca, sa, cb, sb, qd, columns, columns_dot);
  Vec3<double> rest = alpha;
  for (int i = 0; i < 3; ++i) rest -= columns_dot[i] * qd[i];
  const Vec3<double> second = lu.solve(rest);
  for (int i = 0; i < 3; ++i) qdd[i] = second[i];
  return "";
}

// The angles of r in `order` and their derivatives (euler_order.h): the 1-2-3 angles of
// P^T r Q^T with w and alpha in P's frame, then beta = beta' - shift, gamma = sign gamma'.
std::string ordered_angles_coordinates(EulerOrder order, const Mat3<double>& r,
                                       const Vec3<double>& w, const Vec3<double>& alpha, double* q,
                                       double* qd, double* qdd) {
  const EulerMap& map = euler_map(order);
  const Mat3<double> pt = map.p.matrix().transpose();
  const std::string error =
      angles_123_coordinates(pt * r * map.q.matrix().transpose(), pt * w, pt * alpha, q, qd, qdd);
  if (!error.empty())
    return "base orientation " + error + " of the " + to_string(order) + " angles";
  if (map.shifted) q[1] -= M_PI / 2;
  q[2] *= map.gamma_sign;
  qd[2] *= map.gamma_sign;
  if (qdd) qdd[2] *= map.gamma_sign;
  return "";
}

}  // namespace

std::string free_joint_coordinates(const Joint& joint, const BaseMotion& m, double* q, double* qd,
                                   double* qdd) {
  if (joint.type != JointType::kFree123 && joint.type != JointType::kFreeEuler)
    return "joint '" + joint.name + "' is not a free joint";
  const Mat3<double> ct = joint.rotation.transpose();  // R (= Bj) to the joint frame
  const Vec3<double> s = ct * (m.position - joint.offset), sd = ct * m.velocity;
  for (int i = 0; i < 3; ++i) {
    q[i] = s[i];
    qd[i] = sd[i];
  }
  if (qdd) {
    const Vec3<double> sdd = ct * m.acceleration;
    for (int i = 0; i < 3; ++i) qdd[i] = sdd[i];
  }
  const Mat3<double> r = ct * m.rotation;
  const Vec3<double> w = ct * m.omega, alpha = ct * m.alpha;
  if (joint.type == JointType::kFreeEuler) {
    euler_coordinates(r, w, alpha, q + 3, qd + 3, qdd ? qdd + 3 : nullptr);
    return "";
  }
  return ordered_angles_coordinates(joint.euler_order, r, w, alpha, q + 3, qd + 3,
                                    qdd ? qdd + 3 : nullptr);
}

}  // namespace mbk
