// The error of a kinematics result against a reference, per quantity and overall
// (doc/error_vs_runtime.md): for each quantity Q in {orientation, omega, alpha, p, v, a}
// the largest over bodies of |Q_k - Q_ref,k| divided by that quantity's scale, the largest
// |Q_ref,k| over bodies (1 for orientation; a quantity whose scale is 0 is compared absolutely).
// Vector norms are Euclidean, the orientation's is the Frobenius norm of S0K - S0K_ref. p is
// the mass center position, v and a its velocity and acceleration.
#pragma once

#include <algorithm>
#include <array>
#include <string>

#include "mb_kinematics/core/data.h"

namespace mbk {

// The quantities compared, an index into KinematicsError::relative; scoped (ErrorQuantity::kOmega)
// so they cannot be mistaken for the glyphs' GlyphQuantity. Velocity and acceleration: of G_k.
struct ErrorQuantity {
  enum Index { kOrientation, kOmega, kAlpha, kPosition, kVelocity, kAcceleration, kCount };
};
const char* quantity_name(int q);

struct KinematicsError {
  std::array<double, ErrorQuantity::kCount> relative{};  // per quantity, as above
  double max() const { return *std::max_element(relative.begin(), relative.end()); }
};

namespace detail {

template <typename S>
const std::vector<Vec3<S>>& quantity_vectors(const Data<S>& d, int q) {
  switch (q) {
    case ErrorQuantity::kOmega:
      return d.omega;
    case ErrorQuantity::kAlpha:
      return d.alpha;
    case ErrorQuantity::kPosition:
      return d.mass_center;
    case ErrorQuantity::kVelocity:
      return d.mass_center_velocity;
    default:
      return d.mass_center_acceleration;
  }
}

}  // namespace detail

// `levels` limits the comparison: kPose compares orientation and position only,
// ErrorQuantity::kVelocity adds omega and v. Both Data are converted to long double before
// subtracting.
template <typename S, typename R>
KinematicsError kinematics_error(const Data<S>& data, const Data<R>& reference,
                                 Level level = Level::kAcceleration) {
  using L = long double;
  KinematicsError e;
  const size_t n = reference.rotation.size();
  for (size_t k = 1; k < n; ++k) {
    const Mat3<L> dr =
        data.rotation[k].template cast<L>() - reference.rotation[k].template cast<L>();
    e.relative[ErrorQuantity::kOrientation] =
        std::max(e.relative[ErrorQuantity::kOrientation], double(dr.norm()));
  }
  for (int q = ErrorQuantity::kOmega; q < ErrorQuantity::kCount; ++q) {
    const bool wanted = q == ErrorQuantity::kPosition ||
                        (q == ErrorQuantity::kOmega || q == ErrorQuantity::kVelocity
                             ? level != Level::kPose
                             : level == Level::kAcceleration);
    if (!wanted) continue;
    const auto& got = detail::quantity_vectors(data, q);
    const auto& ref = detail::quantity_vectors(reference, q);
    L scale = 0, worst = 0;
    for (size_t k = 1; k < n; ++k) {
      const Vec3<L> r = ref[k].template cast<L>();
      scale = std::max(scale, r.norm());
      worst = std::max(worst, (got[k].template cast<L>() - r).norm());
    }
    e.relative[q] = double(scale > 0 ? worst / scale : worst);
  }
  return e;
}

}  // namespace mbk
