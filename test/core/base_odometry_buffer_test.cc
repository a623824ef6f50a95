// The node's odometry buffer (estimation/base_odometry_buffer.h): it interpolates, holds and
// refuses as documented, and its estimator gives the acceleration of motions it differentiates
// exactly.
#include "mb_kinematics/estimation/base_odometry_buffer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using V = mbk::Vec3<double>;
using Fit = mbk::BaseOdometryBuffer::Fit;
constexpr double kTol = 1e-12;

void expect_near(const V& a, const V& b, double tol, const char* what) {
  EXPECT_LT((a - b).norm(), tol) << what << ": " << a.transpose() << " vs " << b.transpose();
}

mbk::BaseSample sample(double t, double angle, const V& p, const V& linear, const V& angular) {
  mbk::BaseSample s;
  s.t = t;
  s.position = p;
  s.orientation = Eigen::AngleAxisd(angle, V::UnitZ());
  s.linear = linear;
  s.angular = angular;
  return s;
}

// Turning about z only: the twist in R is the body-frame twist turned by the interpolated yaw.
TEST(BaseOdometryBuffer, InterpolatesPoseBySlerpAndTwistLinearly) {
  auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk::BaseOdometryBuffer buffer(*estimator, 0.5);
  ASSERT_EQ(buffer.add(sample(10.0, 0.0, V(0, 0, 0), V(1, 0, 0), V(0, 0, 0.2))), "");
  ASSERT_EQ(buffer.add(sample(10.4, 0.8, V(0.4, 0.8, 0), V(3, 0, 0), V(0, 0, 0.6))), "");
  mbk::BaseMotion m;
  bool has_acceleration = true;
  ASSERT_EQ(buffer.at(10.1, m, has_acceleration), Fit::kInterpolated);
  const mbk::Mat3<double> r = Eigen::AngleAxisd(0.2, V::UnitZ()).toRotationMatrix();
  EXPECT_LT((m.rotation - r).norm(), kTol);  // a quarter of the way about one axis
  expect_near(m.position, V(0.1, 0.2, 0), kTol, "position");
  const V v0(1, 0, 0), v1 = Eigen::AngleAxisd(0.8, V::UnitZ()) * V(3, 0, 0);
  expect_near(m.velocity, 0.75 * v0 + 0.25 * v1, kTol, "velocity in R");
  expect_near(m.omega, V(0, 0, 0.3), kTol, "omega in R");
  EXPECT_FALSE(has_acceleration) << "the first sample has no derivative";
}

TEST(BaseOdometryBuffer, HoldsWithinTheGapAndRefusesBeyondIt) {
  auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk::BaseOdometryBuffer buffer(*estimator, 0.5);
  mbk::BaseMotion m;
  bool has_acceleration = false;
  EXPECT_EQ(buffer.at(1.0, m, has_acceleration), Fit::kEmpty);
  ASSERT_EQ(buffer.add(sample(10.0, 0.3, V(1, 2, 3), V(1, 0, 0), V(0, 0, 0))), "");
  ASSERT_EQ(buffer.add(sample(10.1, 0.3, V(1, 2, 3), V(1, 0, 0), V(0, 0, 0))), "");
  EXPECT_EQ(buffer.at(10.5, m, has_acceleration), Fit::kHeld);
  EXPECT_TRUE(m.position == V(1, 2, 3)) << "held position";
  EXPECT_EQ(buffer.at(9.6, m, has_acceleration), Fit::kHeld);
  m.position = V(7, 7, 7);
  EXPECT_EQ(buffer.at(10.7, m, has_acceleration), Fit::kTooNew);
  EXPECT_EQ(buffer.at(9.4, m, has_acceleration), Fit::kTooOld);
  EXPECT_TRUE(m.position == V(7, 7, 7)) << "unchanged when refused";
}

TEST(BaseOdometryBuffer, RefusesNonFiniteOdometryAndRestartsWhenStampsGoBack) {
  auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk::BaseOdometryBuffer buffer(*estimator, 0.5);
  ASSERT_EQ(buffer.add(sample(10.0, 0.3, V(1, 2, 3), V(1, 0, 0), V(0, 0, 0))), "");
  mbk::BaseSample bad = sample(10.1, 0.3, V(1, 2, 3), V(1, 0, 0), V(0, 0, 0));
  bad.linear.y() = std::nan("");
  EXPECT_NE(buffer.add(bad), "");
  bad = sample(10.1, 0.3, V(1, 2, 3), V(1, 0, 0), V(0, 0, 0));
  bad.orientation.coeffs().setZero();
  EXPECT_NE(buffer.add(bad), "");
  EXPECT_EQ(buffer.last_stamp(), 10.0);
  ASSERT_EQ(buffer.add(sample(5.0, 0.3, V(0, 0, 0), V(1, 0, 0), V(0, 0, 0))), "");
  EXPECT_EQ(buffer.first_stamp(), 5.0);  // restarted
  mbk::BaseMotion m;
  bool has_acceleration = true;
  EXPECT_EQ(buffer.at(5.0, m, has_acceleration), Fit::kInterpolated);
  EXPECT_FALSE(has_acceleration);  // one sample: no derivative yet
  ASSERT_EQ(buffer.add(sample(5.1, 0.3, V(0, 0, 0), V(1, 0, 0), V(0, 0, 0))), "");
  ASSERT_EQ(buffer.add(sample(8.0, 0.3, V(0, 0, 0), V(1, 0, 0), V(0, 0, 0))), "");
  EXPECT_EQ(buffer.first_stamp(), 8.0);  // a pause longer than the gap: restarted
  EXPECT_EQ(buffer.at(6.5, m, has_acceleration), Fit::kTooOld);  // not across the pause
}

// Constant linear acceleration a in R and constant angular acceleration alpha about z: the
// velocities in R are linear in t, which the 3-point backward difference differentiates exactly.
TEST(BaseOdometryBuffer, AccelerationFromTheEstimatorOnTheVelocitiesInR) {
  auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk::BaseOdometryBuffer buffer(*estimator, 0.5);
  const V a(0.5, -0.2, 0.1), v0(0.3, 0.1, 0);
  const double alpha = 0.7, w0 = 0.2;
  for (int i = 0; i < 600; ++i) {                 // more than the buffer keeps: trimmed on the way
    const double t = 0.02 * i + 0.003 * (i % 2);  // uneven steps
    const double angle = w0 * t + alpha * t * t / 2;
    const mbk::Mat3<double> r = Eigen::AngleAxisd(angle, V::UnitZ()).toRotationMatrix();
    const V v_r = v0 + a * t;
    ASSERT_EQ(
        buffer.add(sample(t, angle, V(0, 0, 0), r.transpose() * v_r, V(0, 0, w0 + alpha * t))), "");
  }
  EXPECT_GT(buffer.first_stamp(), 0.0) << "trimmed";
  mbk::BaseMotion m;
  bool has_acceleration = false;
  ASSERT_EQ(buffer.at(buffer.last_stamp() - 0.01, m, has_acceleration), Fit::kInterpolated);
  ASSERT_TRUE(has_acceleration);
  expect_near(m.acceleration, a, 1e-9, "acceleration");
  expect_near(m.alpha, V(0, 0, alpha), 1e-9, "alpha");
}

}  // namespace
