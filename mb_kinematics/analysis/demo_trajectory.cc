#include "mb_kinematics/analysis/demo_trajectory.h"

#include <cmath>
#include <string>

namespace mbk {

double Wave::at(double t, int order) const {
  const double phase = w * t + p;
  if (order == 0) return b + a * std::sin(phase);
  if (order == 1) return a * w * std::cos(phase);
  return -a * w * w * std::sin(phase);
}

std::vector<Wave> demo_waves(const Model& model) {
  std::vector<Wave> waves(model.nq);
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const JointType type = body.joint.type;
    for (int c = 0; c < coordinate_count(type); ++c) {
      const int i = body.q_index + c;
      const CoordinateKind kind = coordinate_kind(type, c);
      const bool translation = kind == CoordinateKind::kTranslation;
      const bool euler = kind == CoordinateKind::kEulerParameter;
      Wave& w = waves[i];
      w.b = euler && c == first_euler_parameter(type) + 3 ? 1.0 : 0.0;  // e4 = 1: the identity
      w.a = translation ? 0.05 : euler ? 0.2 : 0.4;
      w.w = 2 * M_PI * (0.2 + 0.4 * std::fmod(0.618034 * (i + 1), 1.0));
      w.p = 0.7 * i;
    }
  }
  return waves;
}

}  // namespace mbk
