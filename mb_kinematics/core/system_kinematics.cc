#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

std::vector<std::string> bodies_without_inertia(const Model& model) {
  std::vector<std::string> names;
  for (int k = 0; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    if (body.mass > 0 && !body.has_inertia) names.push_back(body.name);
  }
  return names;
}

bool inertias_known(const Model& model) {
  for (int k = 0; k <= model.body_count(); ++k)
    if (model.bodies[k].mass > 0 && !model.bodies[k].has_inertia) return false;
  return true;
}

}  // namespace mbk
