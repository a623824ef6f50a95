#include "mb_kinematics/core/rotation_errors.h"

#include "mb_kinematics/core/joint_motion.h"

namespace mbk {

namespace {

// The joint's motion at its three angles q (translations 0): its columns E and their rates.
JointMotion<double> angle_motion(const Joint& joint, const double* q, const double* qd) {
  const int t = translation_count(joint.type);
  double qa[6] = {0, 0, 0, 0, 0, 0}, qda[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 3; ++i) qa[t + i] = q[i], qda[t + i] = qd ? qd[i] : 0.0;
  JointMotion<double> m;
  joint_motion(joint, SpeedKind::kCoordinateDerivatives, qa, qda, m);
  return m;
}

// w = E q' and w' = E q'' + E' q' (doc/method.md 4), Bj axes, stacked.
Eigen::Matrix<double, 6, 1> relative_rates(const Joint& joint, const double* q, const double* qd,
                                           const double* qdd) {
  const int t = translation_count(joint.type);
  const JointMotion<double> m = angle_motion(joint, q, qd);
  Eigen::Matrix<double, 6, 1> out = Eigen::Matrix<double, 6, 1>::Zero();
  for (int i = 0; i < 3; ++i) {
    out.head<3>() += m.angular[t + i] * qd[i];
    out.tail<3>() += m.angular[t + i] * qdd[i] + m.angular_dot[t + i] * qd[i];
  }
  return out;
}

Mat3<double> cross_matrix(const Vec3<double>& v) {
  Mat3<double> m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

Mat3<double> angle_rate_matrix(const Joint& joint, const double* angles) {
  const int t = translation_count(joint.type);
  const double zero[3] = {0, 0, 0};
  const JointMotion<double> m = angle_motion(joint, angles, zero);
  Mat3<double> e;
  for (int i = 0; i < 3; ++i) e.col(i) = m.angular[t + i];
  return e;
}

Mat9 angle_error_map(const Joint& joint, const double* q, const double* qd, const double* qdd) {
  constexpr double h = 1e-6;  // rad, rad/s: rates are smooth in both
  Mat9 l = Mat9::Zero();
  const Mat3<double> e = angle_rate_matrix(joint, q);
  for (int b = 0; b < 3; ++b) l.block<3, 3>(3 * b, 3 * b) = e;
  for (int i = 0; i < 3; ++i) {
    double qp[3] = {q[0], q[1], q[2]}, qm[3] = {q[0], q[1], q[2]};
    qp[i] += h, qm[i] -= h;
    l.block<6, 1>(3, i) =
        (relative_rates(joint, qp, qd, qdd) - relative_rates(joint, qm, qd, qdd)) / (2 * h);
    double dp[3] = {qd[0], qd[1], qd[2]}, dm[3] = {qd[0], qd[1], qd[2]};
    dp[i] += h, dm[i] -= h;  // w' is quadratic in q': exact but for rounding
    l.block<3, 1>(6, 3 + i) =
        (relative_rates(joint, q, dp, qdd) - relative_rates(joint, q, dm, qdd)).tail<3>() / (2 * h);
  }
  return l;
}

// Body b's rotation S0B turned by phi, its omega_b and alpha_b moved by u and s (R axes), every
// joint outward of it unchanged: for a body k outward of b, with Omega = omega_k - omega_b,
// Lambda = alpha_k - alpha_b - omega_b x Omega (turned with B), and D = p_k - O_b,
// V = v_k - v_Ob - omega_b x D, A = a_k - a_Ob - alpha_b x D - omega_b x (omega_b x D)
// - 2 omega_b x V (moving with B: turned by phi),
//   d alpha_k = s + u x Omega + omega_b x (phi x Omega) + phi x Lambda,
//   d a_k = s x D + alpha_b x (phi x D) + u x (omega_b x D) + omega_b x (u x D)
//           + omega_b x (omega_b x (phi x D)) + 2 u x V + 2 omega_b x (phi x V) + phi x A.
void add_joint_rotation_variance(const Model& model, const Data<double>& data, int b,
                                 const Mat9& cov, std::vector<Vec3<double>>& alpha_var,
                                 std::vector<Vec3<double>>& acceleration_var,
                                 std::vector<char>& subtree) {
  const int n = model.body_count(), j = model.bodies[b].lower;
  // (phi, u, s) in R from (dtheta, dw, dw') in Bj: phi = S0J dtheta, u = S0J dw,
  // s = S0J dw' + omega_j x S0J dw (alpha_b = alpha_j + S0J w' + omega_j x S0J w).
  const Mat3<double>& s0j = data.rotation[j];
  Mat9 t = Mat9::Zero();
  for (int i = 0; i < 3; ++i) t.block<3, 3>(3 * i, 3 * i) = s0j;
  t.block<3, 3>(6, 3) = cross_matrix(data.omega[j]) * s0j;
  const Mat9 p = t * cov * t.transpose();
  const Vec3<double>&wb = data.omega[b], &ab = data.alpha[b], &ob = data.origin[b];
  const Mat3<double> wx = cross_matrix(wb), ax = cross_matrix(ab);
  subtree.assign(n + 1, 0);
  subtree[b] = 1;
  Eigen::Matrix<double, 3, 9> ja, jl;
  for (int k = b; k <= n; ++k) {
    if (k > b && !subtree[model.bodies[k].lower]) continue;
    subtree[k] = 1;
    const Vec3<double> omega = data.omega[k] - wb, lambda = data.alpha[k] - ab - wb.cross(omega);
    const Vec3<double> d = data.mass_center[k] - ob;
    const Vec3<double> v = data.mass_center_velocity[k] - data.origin_velocity[b] - wb.cross(d);
    const Vec3<double> a = data.mass_center_acceleration[k] - data.origin_acceleration[b] -
                           ab.cross(d) - wb.cross(wb.cross(d)) - 2 * wb.cross(v);
    const Mat3<double> ox = cross_matrix(omega), dx = cross_matrix(d), vx = cross_matrix(v);
    ja << -wx * ox - cross_matrix(lambda), -ox, Mat3<double>::Identity();
    jl << -ax * dx - wx * wx * dx - 2 * wx * vx - cross_matrix(a),
        -cross_matrix(wb.cross(d)) - wx * dx - 2 * vx, -dx;
    alpha_var[k] += (ja * p * ja.transpose()).diagonal();
    acceleration_var[k] += (jl * p * jl.transpose()).diagonal();
  }
}

}  // namespace mbk
