#include "mb_kinematics/core/independent_speeds.h"

namespace mbk {

int independent_speed(const Model& model, int r, double& factor) {
  factor = 1.0;
  // Mimics exist only with coordinate-derivative speeds (finalize_model), so speed r is
  // coordinate r. At most one step per mimic: a loop of mimics stops there.
  for (size_t steps = 0; steps <= model.mimics.size(); ++steps) {
    const Mimic* mimic = nullptr;
    for (const Mimic& m : model.mimics)
      if (m.coordinate == r) mimic = &m;
    if (!mimic) break;
    factor *= mimic->multiplier;
    r = mimic->source;
  }
  return r;
}

std::vector<SpeedColumn> independent_columns(const Model& model,
                                             const PartialVelocities<double>& pv, int k) {
  std::vector<SpeedColumn> columns;
  for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i) {
    double f = 1.0;
    const int r = independent_speed(model, pv.speed[i], f);
    SpeedColumn* c = nullptr;
    for (SpeedColumn& existing : columns)
      if (existing.speed == r) c = &existing;
    if (!c) {
      columns.push_back({r, Vec3<double>::Zero(), Vec3<double>::Zero(), Vec3<double>::Zero(),
                         Vec3<double>::Zero()});
      c = &columns.back();
    }
    c->omega += f * pv.omega[i];  // omega_kr y_r = (f omega_kr) y_source
    c->velocity += f * pv.velocity[i];
    c->omega_dot += f * pv.omega_dot[i];
    c->velocity_dot += f * pv.velocity_dot[i];
  }
  return columns;
}

}  // namespace mbk
