// fixed_point (core/point_kinematics.h): the velocity and acceleration of a point fixed in a
// body against central differences of its position and velocity along a closed-form motion, and
// its levels (kPose and kVelocity give the parts they promise, the same bits as kAcceleration).
#include "mb_kinematics/core/point_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;

// A body whose point O moves on o(t) = (t^2, sin t, cos 2t), turning about the fixed axis u by
// the angle theta(t) = t^2 / 2 + t: omega = theta' u, alpha = theta'' u.
const V kAxis = V(1.0, -2.0, 2.0).normalized();
V o(double t) { return V(t * t, std::sin(t), std::cos(2 * t)); }
V o_dot(double t) { return V(2 * t, std::cos(t), -2 * std::sin(2 * t)); }
V o_ddot(double t) { return V(2.0, -std::sin(t), -4 * std::cos(2 * t)); }
M rotation(double t) { return Eigen::AngleAxisd(t * t / 2 + t, kAxis).toRotationMatrix(); }

// The point r (body components) of that body at t.
mbk::PointMotion<V> point(double t, const V& r) {
  const mbk::PointMotion<V> origin{o(t), o_dot(t), o_ddot(t)};
  return mbk::fixed_point(origin, V((t + 1) * kAxis), V(kAxis), V(rotation(t) * r));
}

TEST(PointKinematics, IsTheTimeDerivativeOfThePointsPositionAndVelocity) {
  const V r(0.3, -0.7, 1.1);
  const double h = 1e-5;  // central differences: error ~h^2 |f'''| ~ 1e-9
  for (double t : {-0.8, 0.0, 0.4, 1.3}) {
    const mbk::PointMotion<V> before = point(t - h, r), at = point(t, r), after = point(t + h, r);
    EXPECT_LT(((after.position - before.position) / (2 * h) - at.velocity).norm(), 1e-8) << t;
    EXPECT_LT(((after.velocity - before.velocity) / (2 * h) - at.acceleration).norm(), 1e-8) << t;
  }
}

TEST(PointKinematics, LevelsGiveTheSameBits) {
  const mbk::PointMotion<V> origin{o(0.6), o_dot(0.6), o_ddot(0.6)};
  const V omega(0.2, -1.0, 0.5), alpha(-0.3, 0.4, 2.0), rho(0.1, 0.9, -0.4);
  const mbk::PointMotion<V> full = mbk::fixed_point(origin, omega, alpha, rho);
  const mbk::PointMotion<V> velocity =
      mbk::fixed_point<mbk::Level::kVelocity>(origin, omega, alpha, rho);
  const mbk::PointMotion<V> pose = mbk::fixed_point<mbk::Level::kPose>(origin, omega, alpha, rho);
  EXPECT_EQ(full.position, o(0.6) + rho);
  EXPECT_EQ(velocity.position, full.position);
  EXPECT_EQ(velocity.velocity, full.velocity);
  EXPECT_EQ(pose.position, full.position);
}

}  // namespace
