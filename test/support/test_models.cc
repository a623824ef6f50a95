#include "test/support/test_models.h"

#include <cmath>

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/io/rpy.h"

namespace mbk_test {

std::string source_path(const std::string& relative) {
  return std::string(MBK_SOURCE_DIR) + "/" + relative;
}

mbk::Model random_tree(int n, unsigned seed, mbk::SpeedKind speeds) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const mbk::JointType types[] = {mbk::JointType::kFixed,     mbk::JointType::kRevolute,
                                  mbk::JointType::kPrismatic, mbk::JointType::kBall123,
                                  mbk::JointType::kBallEuler, mbk::JointType::kFree123,
                                  mbk::JointType::kFreeEuler, mbk::JointType::kPlanar};
  mbk::Model model;
  model.speeds = speeds;
  model.bodies.resize(n + 1);
  for (int k = 1; k <= n; ++k) {
    mbk::Body& body = model.bodies[k];
    body.name = "b" + std::to_string(k);
    // Mostly the previous body (deep chains), sometimes any earlier one (branches).
    body.lower = (k == 1) ? 0 : (rng() % 3 ? k - 1 : static_cast<int>(rng() % k));
    body.joint.name = "j" + std::to_string(k);
    body.joint.type = types[rng() % 8];
    body.joint.axis = mbk::Vec3<double>(u(rng), u(rng), u(rng)).normalized();
    body.joint.offset = mbk::Vec3<double>(u(rng), u(rng), u(rng));
    body.joint.rotation = mbk::rotation_from_rpy(3 * u(rng), 1.5 * u(rng), 3 * u(rng));
    body.mass_center = mbk::Vec3<double>(u(rng), u(rng), u(rng));
    body.mass = 1.0 + u(rng) * 0.5;
  }
  mbk::finalize_model(model);
  return model;
}

mbk::Model revolute_chain(int n) {
  mbk::Model model;
  model.bodies.resize(n + 1);
  for (int k = 1; k <= n; ++k) {
    mbk::Body& body = model.bodies[k];
    body.name = "link" + std::to_string(k);
    body.lower = k - 1;
    body.joint.name = "joint" + std::to_string(k);
    body.joint.type = mbk::JointType::kRevolute;
    body.joint.axis = k % 2 ? mbk::Vec3<double>::UnitZ() : mbk::Vec3<double>::UnitY();
    if (k > 1) body.joint.offset = mbk::Vec3<double>(1.0, 0.0, 0.0);
    body.mass_center = mbk::Vec3<double>(0.5, 0.0, 0.0);
    body.mass = 1.0;
  }
  mbk::finalize_model(model);
  return model;
}

Trajectory::Trajectory(const mbk::Model& m, unsigned seed) : model(&m) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int nq = m.nq;
  b.resize(nq);
  a.resize(nq);
  w.resize(nq);
  p.resize(nq);
  for (int i = 0; i < nq; ++i) {
    b[i] = u(rng);
    a[i] = u(rng);
    w[i] = 0.5 + 1.5 * std::abs(u(rng));
    p[i] = 3 * u(rng);
  }
  for (int k = 1; k <= m.body_count(); ++k) {
    const mbk::Body& body = m.bodies[k];
    if (!mbk::uses_euler_parameters(body.joint.type)) continue;
    const int e4 = body.q_index + mbk::coordinate_count(body.joint.type) - 1;
    b[e4] = 2.0;  // |e| stays >= 1: e4 in [1, 3]
  }
}

template <typename S>
mbk::JointState<S> Trajectory::at(double t) const {
  mbk::JointState<S> state(*model);
  for (int i = 0; i < model->nq; ++i) {
    const S phase = S(w[i]) * S(t) + S(p[i]);
    using std::cos;
    using std::sin;
    state.position[i] = S(b[i]) + S(a[i]) * sin(phase);
    state.velocity[i] = S(a[i]) * S(w[i]) * cos(phase);
    state.acceleration[i] = -S(a[i]) * S(w[i]) * S(w[i]) * sin(phase);
  }
  return state;
}

template mbk::JointState<double> Trajectory::at<double>(double) const;
template mbk::JointState<long double> Trajectory::at<long double>(double) const;

mbk::JointState<double> state_with_angular_speeds(const mbk::Model& quasi_model,
                                                  const mbk::Model& coordinate_model,
                                                  const Trajectory& trajectory, double t) {
  const mbk::JointState<double> full = trajectory.at<double>(t);
  mbk::JointState<double> state(quasi_model);
  state.position = full.position;
  mbk::JointMotion<double> m;
  for (int k = 1; k <= quasi_model.body_count(); ++k) {
    const mbk::Body& qb = quasi_model.bodies[k];
    const mbk::Body& cb = coordinate_model.bodies[k];
    const int nq = mbk::coordinate_count(cb.joint.type);
    if (!mbk::uses_euler_parameters(cb.joint.type)) {
      for (int i = 0; i < nq; ++i) {
        state.velocity[qb.v_index + i] = full.velocity[cb.v_index + i];
        state.acceleration[qb.v_index + i] = full.acceleration[cb.v_index + i];
      }
      continue;
    }
    // Translations (free joints) carry over; the rotation speeds become C_k^T w_k in the
    // joint frame: the joint's columns with the identity offset rotation give them directly.
    mbk::Joint joint = cb.joint;
    joint.rotation.setIdentity();
    const double* q = full.position.data() + cb.q_index;
    const double* y = full.velocity.data() + cb.v_index;
    const double* yd = full.acceleration.data() + cb.v_index;
    mbk::joint_motion(joint, mbk::SpeedKind::kCoordinateDerivatives, q, y, m);
    const int t0 = nq - 4;  // number of translations
    for (int i = 0; i < t0; ++i) {
      state.velocity[qb.v_index + i] = y[i];
      state.acceleration[qb.v_index + i] = yd[i];
    }
    mbk::Vec3<double> w = mbk::Vec3<double>::Zero(), wd = mbk::Vec3<double>::Zero();
    for (int c = t0; c < nq; ++c) {
      w += m.angular[c] * y[c];
      wd += m.angular[c] * yd[c] + m.angular_dot[c] * y[c];
    }
    state.velocity.segment<3>(qb.v_index + t0) = w;
    state.acceleration.segment<3>(qb.v_index + t0) = wd;
  }
  return state;
}

}  // namespace mbk_test
