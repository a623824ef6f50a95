#include "mb_kinematics/analysis/model_generators.h"

#include <cmath>

#include "mb_kinematics/core/rpy.h"

namespace mbk {
Model make_chain(int n, JointType type) {
  Model model;
  model.bodies.resize(n + 1);
  for (int k = 1; k <= n; ++k) {
    Body& body = model.bodies[k];
    body.name = "link" + std::to_string(k);
    body.lower = k - 1;
    body.joint.name = "joint" + std::to_string(k);
    body.joint.type = type;
    body.joint.axis = k % 2 ? Vec3<double>::UnitZ() : Vec3<double>::UnitY();
    if (k > 1) body.joint.offset = Vec3<double>(1.0, 0.0, 0.0);
    body.mass_center = Vec3<double>(0.5, 0.0, 0.0);
    body.mass = 1.0;
  }
  finalize_model(model);
  return model;
}

Model make_random_tree(int n, unsigned seed, SpeedKind speeds) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<JointType>& types = all_joint_types();
  Model model;
  model.speeds = speeds;
  model.bodies.resize(n + 1);
  for (int k = 1; k <= n; ++k) {
    Body& body = model.bodies[k];
    body.name = "b" + std::to_string(k);
    body.lower = k == 1 ? 0 : (rng() % 3 ? k - 1 : static_cast<int>(rng() % k));
    body.joint.name = "j" + std::to_string(k);
    body.joint.type = types[rng() % types.size()];
    body.joint.axis = Vec3<double>(u(rng), u(rng), u(rng)).normalized();
    body.joint.offset = Vec3<double>(u(rng), u(rng), u(rng));
    body.joint.rotation = rotation_from_rpy(3 * u(rng), 1.5 * u(rng), 3 * u(rng));
    body.mass_center = Vec3<double>(u(rng), u(rng), u(rng));
    body.mass = 1.0 + 0.5 * u(rng);
  }
  finalize_model(model);
  return model;
}

Model make_random_revolute_tree(int n, unsigned seed) {
  Model model = make_random_tree(n, seed);
  for (int k = 1; k <= n; ++k) model.bodies[k].joint.type = JointType::kRevolute;
  finalize_model(model);
  return model;
}

Model with_euler_parameters(const Model& model, SpeedKind speeds) {
  Model out = model;
  out.speeds = speeds;
  for (Body& body : out.bodies) {
    if (body.joint.type == JointType::kBall123) body.joint.type = JointType::kBallEuler;
    if (body.joint.type == JointType::kFree123) body.joint.type = JointType::kFreeEuler;
  }
  finalize_model(out);
  return out;
}

JointState<double> random_state(const Model& model, std::mt19937& rng, double speed_scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  JointState<double> state(model);
  for (int i = 0; i < model.nq; ++i) state.position[i] = M_PI * u(rng);
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    if (!uses_euler_parameters(body.joint.type)) continue;
    const int e = body.q_index + coordinate_count(body.joint.type) - 4;
    state.position.segment<4>(e) = Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized();
  }
  for (int i = 0; i < model.nv; ++i) {
    state.velocity[i] = speed_scale * u(rng);
    state.acceleration[i] = speed_scale * speed_scale * u(rng);
  }
  apply_mimics(model, state);
  return state;
}

Model with_random_inertias(Model model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> moment(0.1, 1.0), angle(-3.0, 3.0), t(0.0, 1.0);
  for (int k = 1; k <= model.body_count(); ++k) {
    Body& body = model.bodies[k];
    if (body.has_inertia) continue;
    const double a = moment(rng), b = moment(rng);
    const double c = std::abs(a - b) + t(rng) * (a + b - std::abs(a - b));  // triangle inequality
    const Mat3<double> r = rotation_123(angle(rng), angle(rng), angle(rng));
    body.inertia = r * Vec3<double>(a, b, c).asDiagonal() * r.transpose();
    body.has_inertia = true;
  }
  finalize_model(model);
  return model;
}

}  // namespace mbk
