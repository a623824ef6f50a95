#include "mb_kinematics/core/error_indicators.h"

#include <algorithm>
#include <cmath>

namespace mbk {

double orthonormality_drift(const Data<double>& data) {
  double drift = 0;
  for (size_t k = 1; k < data.rotation.size(); ++k) {
    const Mat3<double>& r = data.rotation[k];
    drift = std::max(drift, (r.transpose() * r - Mat3<double>::Identity()).norm());
  }
  return drift;
}

double euler_norm_error(const Model& model, const JointState<double>& state) {
  double error = 0;
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    if (!uses_euler_parameters(body.joint.type)) continue;
    const int e = body.q_index + first_euler_parameter(body.joint.type);
    error = std::max(error, std::abs(state.position.segment<4>(e).norm() - 1.0));
  }
  return error;
}

double prediction_residual(const JointState<double>& previous, const JointState<double>& current,
                           double dt) {
  // One expression, evaluated in one pass without a vector for the prediction (the node takes
  // the residual of every sample): each coefficient's operations as with one.
  return (current.position -
          (previous.position + previous.velocity * dt + previous.acceleration * (dt * dt / 2)))
      .lpNorm<Eigen::Infinity>();
}

}  // namespace mbk
