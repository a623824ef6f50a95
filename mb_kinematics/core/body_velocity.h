// The motion of a point fixed in body Bk, from the Data of forward_kinematics, with its
// components in R or in Bk (as Pinocchio's getVelocity(..., ReferenceFrame)): a change of
// reference point and of frame, for outputs that want them in the body's own frame.
#pragma once

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/point_kinematics.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

// The frame whose components a vector is given in.
enum class ReferenceFrame { kInertial, kBody };  // R, or Bk itself

// The angular part (omega_k or alpha_k) and the linear part (of the point) of a body's motion.
template <typename S>
struct BodyMotion {
  Vec3<S> angular, linear;
};

namespace detail {

template <typename S>
BodyMotion<S> in_frame(const Data<S>& data, int k, ReferenceFrame frame, BodyMotion<S> m) {
  if (frame == ReferenceFrame::kBody) {  // S0K^T: components in Bk
    m.angular = data.rotation[k].transpose() * m.angular;
    m.linear = data.rotation[k].transpose() * m.linear;
  }
  return m;
}

}  // namespace detail

// omega_k and the velocity of the point P at r from O_k (components in Bk; r = 0: O_k itself,
// r = r_k: G_k): v_P = vO_k + omega_k x (S0K r). Needs Level kVelocity.
template <typename S>
BodyMotion<S> point_velocity(const Data<S>& data, int k, const Vec3<S>& r, ReferenceFrame frame) {
  const PointMotion<Vec3<S>> p = body_point<Level::kVelocity>(data, k, r);
  return detail::in_frame(data, k, frame, BodyMotion<S>{data.omega[k], p.velocity});
}

// alpha_k and the acceleration of the same point:
// a_P = aO_k + alpha_k x (S0K r) + omega_k x (omega_k x (S0K r)). Needs Level kAcceleration.
template <typename S>
BodyMotion<S> point_acceleration(const Data<S>& data, int k, const Vec3<S>& r,
                                 ReferenceFrame frame) {
  const PointMotion<Vec3<S>> p = body_point<Level::kAcceleration>(data, k, r);
  return detail::in_frame(data, k, frame, BodyMotion<S>{data.alpha[k], p.acceleration});
}

}  // namespace mbk
