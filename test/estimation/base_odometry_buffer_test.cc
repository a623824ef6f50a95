// The node's odometry buffer (estimation/base_odometry_buffer.h): it interpolates, holds,
// extrapolates (only when told to) and refuses as documented, exactly on a motion slerp and lerp
// follow exactly, and its estimator gives the acceleration of motions it differentiates exactly.
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

// Constant linear velocity v and constant angular velocity w about a fixed axis, both in R:
// p = p0 + v t, R = exp(t [w]x) R0, the twist constant in R (given in the base's frame).
class ConstantTwist {
 public:
  mbk::BaseSample at(double t) const {
    mbk::BaseSample s;
    s.t = t;
    s.position = p0_ + v_ * t;
    s.orientation = Eigen::AngleAxisd(w_.norm() * t, w_.normalized()) * q0_;
    s.linear = s.orientation.conjugate() * v_;
    s.angular = s.orientation.conjugate() * w_;
    return s;
  }
  const V& v() const { return v_; }
  const V& w() const { return w_; }

 private:
  V p0_{0.4, -1.2, 0.9}, v_{0.7, -0.3, 0.2}, w_{0.9, -1.6, 0.5};
  Eigen::Quaterniond q0_{Eigen::AngleAxisd(0.6, V(1, 1, 0).normalized())};
};

void expect_exact(const mbk::BaseMotion& m, const mbk::BaseSample& s, const ConstantTwist& motion) {
  EXPECT_LT((m.rotation - s.orientation.toRotationMatrix()).norm(), kTol) << "at " << s.t;
  expect_near(m.position, s.position, kTol, "position");
  expect_near(m.velocity, motion.v(), kTol, "velocity in R");
  expect_near(m.omega, motion.w(), kTol, "omega in R");
  expect_near(m.acceleration, V::Zero(), 1e-9, "acceleration");
  expect_near(m.alpha, V::Zero(), 1e-9, "alpha");
}

// Odometry at 100 Hz read half a period after each sample: exact to 1e-12.
TEST(BaseOdometryBuffer, InterpolationIsExactOnAConstantTwistAboutAFixedAxis) {
  auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk::BaseOdometryBuffer buffer(*estimator, 0.5);
  const ConstantTwist motion;
  for (int i = 0; i < 40; ++i) {
    const double t = 3.0 + 0.01 * i;
    ASSERT_EQ(buffer.add(motion.at(t)), "");
    EXPECT_TRUE(buffer.covers(t));
    EXPECT_FALSE(buffer.covers(t + 0.005)) << "the later odometry has not come yet";
    if (i < 3) continue;  // the estimator's first samples
    mbk::BaseMotion m;
    bool has_acceleration = false;
    ASSERT_EQ(buffer.at(t - 0.005, m, has_acceleration), Fit::kInterpolated);
    EXPECT_TRUE(has_acceleration);
    expect_exact(m, motion.at(t - 0.005), motion);
  }
}

// Beyond the last sample (and before the first) the motion is held unless extrapolation is
// asked for; extrapolated, a constant twist is exact; each is flagged by its Fit.
TEST(BaseOdometryBuffer, ExtrapolationIsOffByDefaultAndFlaggedWhenOn) {
  auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk::BaseOdometryBuffer buffer(*estimator, 0.5);
  const ConstantTwist motion;
  for (int i = 0; i < 10; ++i) ASSERT_EQ(buffer.add(motion.at(0.01 * i)), "");
  mbk::BaseMotion m;
  bool has_acceleration = false;
  for (const double t : {0.09 + 0.03, -0.02}) {
    const mbk::BaseSample end = motion.at(t > 0 ? 0.09 : 0.0);
    ASSERT_EQ(buffer.at(t, m, has_acceleration), Fit::kHeld) << t;
    expect_near(m.position, end.position, kTol, "held position");
    EXPECT_LT((m.rotation - end.orientation.toRotationMatrix()).norm(), kTol);
    ASSERT_EQ(buffer.at(t, m, has_acceleration, true), Fit::kExtrapolated) << t;
    EXPECT_LT((m.rotation - motion.at(t).orientation.toRotationMatrix()).norm(), kTol);
    expect_near(m.position, motion.at(t).position, kTol, "extrapolated position");
    expect_near(m.velocity, motion.v(), kTol, "extrapolated velocity");
    expect_near(m.omega, motion.w(), kTol, "extrapolated omega");
  }
  EXPECT_EQ(buffer.at(0.09 + 0.6, m, has_acceleration, true), Fit::kTooNew) << "not beyond the gap";
}

}  // namespace
