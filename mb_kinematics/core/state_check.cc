#include "mb_kinematics/core/state_check.h"

#include <cmath>
#include <cstdio>

namespace mbk {
namespace {

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

std::string where(const Model& model, int k, const std::string& kind, const std::string& name) {
  return "body " + std::to_string(k) + " '" + model.bodies[k].name + "', " + kind + " '" + name +
         "': ";
}

// Message for one value, "" if fine.
std::string check_value(double x, bool bounded) {
  if (!std::isfinite(x)) return "not finite (" + number(x) + ")";
  if (bounded && std::abs(x) > kMaxStateMagnitude)
    return "magnitude " + number(x) + " above the limit 1e50 (the kinematics would overflow)";
  return "";
}

// Every value finite and within kMaxStateMagnitude (angles too), every |e|^2 of Euler parameters
// at least kMinEulerNormSquared: the common case, checked without names or strings. False
// leaves the verdict to first_problem (an angle beyond the limit is fine there).
bool plainly_valid(const Model& model, const JointState<double>& state) {
  // first_euler_parameter of every joint type, looked up once.
  static const std::vector<int> first_e = [] {
    std::vector<int> first;
    for (JointType type : all_joint_types()) first.push_back(first_euler_parameter(type));
    return first;
  }();
  const auto within = [](const Eigen::VectorXd& x) {
    // x * 0 sums to NaN if some x is Inf or NaN: two vectorized passes, no branch per number.
    return x.size() == 0 ||
           ((x.array() * 0.0).sum() == 0.0 && x.cwiseAbs().maxCoeff() <= kMaxStateMagnitude);
  };
  if (!within(state.position) || !within(state.velocity) || !within(state.acceleration))
    return false;
  for (int k = 1; k <= model.body_count(); ++k) {
    const int first = first_e[static_cast<size_t>(model.bodies[k].joint.type)];
    if (first < 0) continue;
    const int e = model.bodies[k].q_index + first;
    if (!(state.position.segment<4>(e).squaredNorm() >= kMinEulerNormSquared)) return false;
  }
  return true;
}

// The first value that is wrong, named, or "".
std::string first_problem(const Model& model, const JointState<double>& state) {
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const JointType type = body.joint.type;
    const int nq = coordinate_count(type), nv = speed_count(type, model.speeds);
    for (int i = 0; i < nq; ++i) {
      const std::string problem = check_value(
          state.position[body.q_index + i],
          coordinate_kind(type, i) != CoordinateKind::kAngle);  // angles may be unbounded
      if (!problem.empty())
        return where(model, k, "coordinate", model.coordinate_names[body.q_index + i]) + problem;
    }
    for (int i = 0; i < nv; ++i) {
      const std::string& name = model.speed_names[body.v_index + i];
      std::string problem = check_value(state.velocity[body.v_index + i], true);
      if (!problem.empty()) return where(model, k, "speed", name) + problem;
      problem = check_value(state.acceleration[body.v_index + i], true);
      if (!problem.empty()) return where(model, k, "acceleration of", name) + problem;
    }
    if (uses_euler_parameters(type)) {
      const int e = body.q_index + first_euler_parameter(type);
      const double n2 = state.position.segment<4>(e).squaredNorm();
      if (!(n2 >= kMinEulerNormSquared)) {
        const std::string& first = model.coordinate_names[e];
        const std::string name = first.substr(0, first.size() - 2) + "e1..e4";
        return where(model, k, "coordinates", name) + "Euler parameters of |e|^2 = " + number(n2) +
               ", below 1e-12 (not a rotation)";
      }
    }
  }
  return "";
}

}  // namespace

std::string check_state(const Model& model, const JointState<double>& state) {
  if (state.position.size() != model.nq || state.velocity.size() != model.nv ||
      state.acceleration.size() != model.nv)
    return "state sized for another model (" + std::to_string(state.position.size()) +
           " coordinates, " + std::to_string(state.velocity.size()) + " speeds; the model has " +
           std::to_string(model.nq) + " and " + std::to_string(model.nv) + ")";
  return plainly_valid(model, state) ? "" : first_problem(model, state);
}

}  // namespace mbk
