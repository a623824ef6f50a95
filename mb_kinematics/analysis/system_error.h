// The error of the system quantities (core/system_kinematics.h) against a reference: for each of
// p_G, v_G, a_G, M v_G and H_G, |x - x_ref| divided by the magnitude its rounding is relative
// to (the reference may cancel to near zero, e.g. a symmetric system): the mass-weighted mean
// of |p_k|, |v_k|, |a_k|, M times that of |v_k|, and sum_k |S0K I_k S0K^T omega_k| +
// m_k |p_k - p_G| |v_k - v_G| (all of the reference). The largest of them.
#pragma once

#include <algorithm>

#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

template <typename S, typename R>
double system_error(const Model& model, const SystemKinematics<S>& got,
                    const SystemKinematics<R>& ref, const Data<R>& ref_data) {
  using L = long double;
  L p = 0, v = 0, a = 0, h = 0;
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& b = model.bodies[k];
    const Vec3<L> omega = ref_data.omega[k].template cast<L>();
    const Mat3<L> s0k = ref_data.rotation[k].template cast<L>();
    p += L(b.mass) * ref_data.mass_center[k].template cast<L>().norm();
    v += L(b.mass) * ref_data.mass_center_velocity[k].template cast<L>().norm();
    a += L(b.mass) * ref_data.mass_center_acceleration[k].template cast<L>().norm();
    const Vec3<L> rel_p = (ref_data.mass_center[k] - ref.mass_center).template cast<L>();
    const Vec3<L> rel_v = (ref_data.mass_center_velocity[k] - ref.velocity).template cast<L>();
    if (b.has_inertia) h += (s0k * b.inertia.cast<L>() * s0k.transpose() * omega).norm();
    h += L(b.mass) * rel_p.norm() * rel_v.norm();
  }
  const L m = L(ref.mass);
  auto err = [](const Vec3<S>& x, const Vec3<R>& y, L scale) {
    const L e = (x.template cast<L>() - y.template cast<L>()).norm();
    return double(scale > 0 ? e / scale : e);
  };
  double worst = std::max({err(got.mass_center, ref.mass_center, p / m),
                           err(got.velocity, ref.velocity, v / m),
                           err(got.acceleration, ref.acceleration, a / m),
                           err(got.linear_momentum, ref.linear_momentum, v)});
  if (ref.angular_momentum_known)
    worst = std::max(worst, err(got.angular_momentum, ref.angular_momentum, h));
  return worst;
}

}  // namespace mbk
