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
    const auto& suffixes = coordinate_suffixes(body.joint.type);
    for (size_t c = 0; c < suffixes.size(); ++c) {
      const int i = body.q_index + static_cast<int>(c);
      const std::string& s = suffixes[c];
      const bool translation =
          body.joint.type == JointType::kPrismatic || s == "x" || s == "y" || s == "z";
      const bool euler = s.size() == 2 && s[0] == 'e';
      Wave& w = waves[i];
      w.b = s == "e4" ? 1.0 : 0.0;
      w.a = translation ? 0.05 : euler ? 0.2 : 0.4;
      w.w = 2 * M_PI * (0.2 + 0.4 * std::fmod(0.618034 * (i + 1), 1.0));
      w.p = 0.7 * i;
    }
  }
  return waves;
}

}  // namespace mbk
