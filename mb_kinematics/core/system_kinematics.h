// Whole-system quantities in R from the bodies' kinematics (doc/method.md 9): total mass M, the
// system mass center G with its velocity and acceleration, linear momentum M v_G, and the angular
// momentum about G, H_G = sum_k S0K I_k S0K^T omega_k + m_k (p_k - p_G) x (v_k - v_G).
// Computed only when a caller asks, from a Data already filled by either formulation.
#pragma once

#include <cassert>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/point_kinematics.h"

namespace mbk {

template <typename S>
struct SystemKinematics {
  S mass = S(0);                               // M = sum_k m_k
  Vec3<S> mass_center = Vec3<S>::Zero();       // p_G = sum_k m_k p_k / M
  Vec3<S> velocity = Vec3<S>::Zero();          // v_G = sum_k m_k v_k / M
  Vec3<S> acceleration = Vec3<S>::Zero();      // a_G = sum_k m_k a_k / M
  Vec3<S> linear_momentum = Vec3<S>::Zero();   // M v_G
  Vec3<S> angular_momentum = Vec3<S>::Zero();  // H_G, when angular_momentum_known
  bool angular_momentum_known = false;         // every body with mass has an inertia
  bool has_mass = false;                       // M > 0: p_G, v_G and a_G are defined
};

// A body with a mass but no inertia: H_G is unknown when any body lacks one.
inline bool lacks_inertia(const Body& body) { return body.mass > 0 && !body.has_inertia; }

// Bodies with a mass but no inertia (their names): H_G is unknown unless this is empty.
std::vector<std::string> bodies_without_inertia(const Model& model);
bool inertias_known(const Model& model);  // bodies_without_inertia is empty (no allocation)

// The mass center of bodies[0] (a URDF's root link, fixed in R's frame; that frame moves as
// data's index 0 says when apply_floating_base set it): the point r_0 of index 0 (body_point).
template <typename S>
void root_mass_center(const Model& model, const Data<S>& data, Vec3<S>& p, Vec3<S>& v, Vec3<S>& a) {
  const PointMotion<Vec3<S>> g =
      body_point(data, 0, Vec3<S>(model.bodies[0].mass_center.template cast<S>()));
  p = g.position;
  v = g.velocity;
  a = g.acceleration;
}

// Fills `out` from `data` at `level` (kPose: M and p_G; kVelocity adds v_G, M v_G and H_G;
// kAcceleration adds a_G). Every link with mass counts, bodies[0] (the root link) included.
// With M = 0 every vector is zero (there is no mass center).
template <typename S>
void system_kinematics(const Model& model, const Data<S>& data, SystemKinematics<S>& out,
                       Level level = Level::kAcceleration) {
  assert(sized_for(data, model) && "system_kinematics: Data made for another model");
  const int n = model.body_count();
  out = SystemKinematics<S>();
  bool inertias = true;  // inertias_known, in the same pass
  for (int k = 0; k <= n; ++k) {
    out.mass += S(model.bodies[k].mass);
    out.has_mass = out.has_mass || model.bodies[k].mass > 0;  // masses are >= 0 (model.cc)
    inertias = inertias && !lacks_inertia(model.bodies[k]);
  }
  out.angular_momentum_known = level != Level::kPose && inertias;
  if (!out.has_mass) return;
  Vec3<S> p0, v0, a0;
  root_mass_center(model, data, p0, v0, a0);
  const auto p = [&](int k) -> const Vec3<S>& { return k ? data.mass_center[k] : p0; };
  const auto v = [&](int k) -> const Vec3<S>& { return k ? data.mass_center_velocity[k] : v0; };
  for (int k = 0; k <= n; ++k) {
    const S m = S(model.bodies[k].mass);
    out.mass_center += m * p(k);
    if (level != Level::kPose) out.linear_momentum += m * v(k);
    if (level == Level::kAcceleration)
      out.acceleration += m * (k ? data.mass_center_acceleration[k] : a0);
  }
  out.mass_center /= out.mass;
  out.velocity = out.linear_momentum / out.mass;
  out.acceleration /= out.mass;
  if (!out.angular_momentum_known) return;
  for (int k = 0; k <= n; ++k) {
    const Body& body = model.bodies[k];
    const Mat3<S>& s0k = data.rotation[k];
    const Vec3<S> local = detail::transpose_product<S>(s0k, data.omega[k]);  // S0K^T omega_k
    const Vec3<S> spin = detail::product<S>(s0k, detail::product<S>(body.inertia.cast<S>(), local));
    const Vec3<S> orbit = (p(k) - out.mass_center).cross(v(k) - out.velocity);
    out.angular_momentum += spin + S(body.mass) * orbit;  // doc/method.md 9, H_G
  }
}

// For double, the same: at kAcceleration on a CPU with AVX2 each body's terms on 256-bit
// vectors (a Vec3 in three lanes), each operation of the template's in its order and without
// fused multiply-adds, so bit for bit the template's (system_kinematics<double>(...) names it;
// test/core/system_kinematics_test.cc compares them); else the template.
void system_kinematics(const Model& model, const Data<double>& data, SystemKinematics<double>& out,
                       Level level = Level::kAcceleration);

}  // namespace mbk
