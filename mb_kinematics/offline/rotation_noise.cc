#include "mb_kinematics/offline/rotation_noise.h"

#include <cmath>

#include "mb_kinematics/core/rotation_errors.h"
#include "mb_kinematics/estimation/auto_estimator.h"

namespace mbk {

std::vector<AngleJoint> angle_joints(const Model& model) {
  std::vector<char> mimic(model.nq, 0);
  for (const Mimic& m : model.mimics) mimic[m.coordinate] = 1;
  std::vector<AngleJoint> out;
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& b = model.bodies[k];
    if (!takes_euler_order(b.joint.type)) continue;
    const int c = b.q_index + translation_count(b.joint.type);
    if (!mimic[c] && !mimic[c + 1] && !mimic[c + 2]) out.push_back({k, c});
  }
  return out;
}

AutoChoice angles_first_chain(AutoChoice choice, const std::vector<AngleJoint>& joints) {
  for (const AngleJoint& j : joints)
    for (int a = 0; a < 3; ++a) choice.centred_choice[j.coordinate + a] = -1;
  return choice;
}

RotationNoise::RotationNoise(const Model& model, double dt)
    : model_(model),
      joints_(angle_joints(model)),
      shortest_(auto_candidates(dt).front()),
      sum_(joints_.size(), Mat3<double>::Zero()) {}

void RotationNoise::add(const std::vector<double>& t, const Segments& segments, const double* x,
                        int ld, int from, int to) {
  for (int i = from; i < to; ++i) {
    derivative_weights(shortest_, t, segments, i, w_);
    count_ += 1;
    if (w_.valid < 2) {  // an unsmoothed sample: interpolated, h_ii = 1
      trace_ += 1;
      continue;
    }
    trace_ += w_.value[(i - w_.begin) / w_.stride];
    for (size_t g = 0; g < joints_.size(); ++g) {
      const int c = joints_[g].coordinate;
      Vec3<double> r;
      for (int a = 0; a < 3; ++a) {
        double fit = 0;
        for (int j = 0; j < w_.count; ++j) fit += w_.value[j] * x[w_.row(j) * ld + c + a];
        r[a] = x[i * ld + c + a] - fit;
      }
      const Vec3<double> rho =
          angle_rate_matrix(model_.bodies[joints_[g].body].joint, x + i * ld + c) * r;
      if (rho.allFinite()) sum_[g] += rho * rho.transpose();  // a bad sample spoils its fits only
    }
  }
}

std::vector<Mat3<double>> RotationNoise::covariance() const {
  std::vector<Mat3<double>> out(sum_.size(), Mat3<double>::Zero());
  if (count_ - trace_ > 0.5)
    for (size_t g = 0; g < sum_.size(); ++g) out[g] = sum_[g] / (count_ - trace_);
  return out;
}

}  // namespace mbk
