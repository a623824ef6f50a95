#include "test/support/test_models.h"

#include <cmath>

#include "mb_kinematics/analysis/model_generators.h"

namespace mbk_test {

std::string source_path(const std::string& relative) {
  return std::string(MBK_SOURCE_DIR) + "/" + relative;
}

mbk::Model random_tree(int n, unsigned seed, mbk::SpeedKind speeds) {
  return mbk::make_random_tree(n, seed, speeds);
}

mbk::Model revolute_chain(int n) { return mbk::make_chain(n, mbk::JointType::kRevolute); }

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
  return mbk::euler_state(coordinate_model, quasi_model, trajectory.at<double>(t));
}

}  // namespace mbk_test
