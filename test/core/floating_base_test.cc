// A floating base (core/floating_base.h): carrying the kinematics into R agrees with the model
// that has the base as a free joint of its own; interpolation and base accelerations against
// closed forms.
#include "mb_kinematics/core/floating_base.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/estimation/base_accelerations.h"
#include "mb_kinematics/io/load_model.h"
#include "test/support/test_models.h"

namespace {

// The model with a massless body "base" on a free_123 joint below every body of `model`.
mbk::Model with_free_base(const mbk::Model& model) {
  mbk::Model out;
  out.frame = model.frame;
  mbk::Body base;
  base.name = "base";
  base.joint.name = "base";
  base.joint.type = mbk::JointType::kFree123;
  out.bodies = {mbk::Body(), base};
  for (int k = 1; k <= model.body_count(); ++k) {
    mbk::Body b = model.bodies[k];
    b.lower += 1;
    out.bodies.push_back(b);
  }
  mbk::finalize_model(out);
  return out;
}

TEST(FloatingBaseTest, CarryingIntoRMatchesAFreeJointBase) {
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/human_body.yaml"));
  const mbk::Model based = with_free_base(model);
  const mbk_test::Trajectory trajectory(based, 7);
  const mbk::JointState<double> full = trajectory.at<double>(0.37);
  mbk::Data<double> expected(based);
  mbk::forward_kinematics(based, full, expected, mbk::Level::kAcceleration);
  mbk::JointState<double> state(model);  // the same joints without the base's six
  state.position = full.position.tail(model.nq);
  state.velocity = full.velocity.tail(model.nv);
  state.acceleration = full.acceleration.tail(model.nv);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
  mbk::BaseMotion base;
  base.rotation = expected.rotation[1];
  base.position = expected.origin[1];
  base.velocity = expected.origin_velocity[1];
  base.acceleration = expected.origin_acceleration[1];
  base.omega = expected.omega[1];
  base.alpha = expected.alpha[1];
  mbk::apply_floating_base(base, data);
  for (int k = 1; k <= model.body_count(); ++k) {
    EXPECT_LT((data.rotation[k] - expected.rotation[k + 1]).norm(), 1e-13) << k;
    EXPECT_LT((data.origin[k] - expected.origin[k + 1]).norm(), 1e-13) << k;
    EXPECT_LT((data.mass_center[k] - expected.mass_center[k + 1]).norm(), 1e-13) << k;
    EXPECT_LT((data.omega[k] - expected.omega[k + 1]).norm(), 1e-12) << k;
    EXPECT_LT((data.alpha[k] - expected.alpha[k + 1]).norm(), 1e-11) << k;
    EXPECT_LT((data.mass_center_velocity[k] - expected.mass_center_velocity[k + 1]).norm(), 1e-12)
        << k;
    EXPECT_LT((data.mass_center_acceleration[k] - expected.mass_center_acceleration[k + 1]).norm(),
              1e-11)
        << k;
    EXPECT_LT((data.origin_acceleration[k] - expected.origin_acceleration[k + 1]).norm(), 1e-11);
  }
}

// A base on a circle of radius 1, turning with it (yaw = w t): its x axis points outwards, so
// its velocity is w along its own y; in R the acceleration is -w^2 (cos, sin, 0).
std::vector<mbk::BaseSample> circle(double w, double rate, double seconds) {
  std::vector<mbk::BaseSample> out;
  for (int i = 0; i < rate * seconds; ++i) {
    mbk::BaseSample s;
    s.t = i / rate;
    s.position << std::cos(w * s.t), std::sin(w * s.t), 0.5;
    s.orientation = Eigen::AngleAxisd(w * s.t, Eigen::Vector3d::UnitZ());
    s.linear << 0, w, 0;
    s.angular << 0, 0, w;
    out.push_back(s);
  }
  return out;
}

TEST(FloatingBaseTest, InterpolationAndAccelerationsOnACircle) {
  const double w = 1.3;
  const std::vector<mbk::BaseSample> samples = circle(w, 100, 2.0);
  std::vector<mbk::Vec3<double>> lin, ang;
  std::vector<int> valid;
  mbk::base_accelerations(samples, mbk::make_offline_estimator("centered_9_4"), 0, lin, ang, valid);
  for (size_t i = 0; i < samples.size(); ++i) {
    ASSERT_EQ(valid[i], 1);
    const double t = samples[i].t;
    EXPECT_LT(
        (lin[i] - mbk::Vec3<double>(-w * w * std::cos(w * t), -w * w * std::sin(w * t), 0)).norm(),
        1e-6)
        << i;
    EXPECT_LT(ang[i].norm(), 1e-9);
  }
  mbk::BaseMotion m;
  const double t = 0.505;  // half way between two samples
  ASSERT_TRUE(mbk::interpolate_base(samples, lin, ang, t, m));
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(w * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((m.rotation - yaw).norm(), 1e-12);  // slerp is exact at a constant rate
  EXPECT_LT((m.omega - mbk::Vec3<double>(0, 0, w)).norm(), 1e-12);
  // Linear interpolation of the position and velocity: chord errors of O((w h)^2 / 8).
  EXPECT_LT((m.velocity - mbk::Vec3<double>(-w * std::sin(w * t), w * std::cos(w * t), 0)).norm(),
            w * std::pow(w * 0.01, 2));
  EXPECT_FALSE(mbk::interpolate_base(samples, lin, ang, 2.5, m));
  EXPECT_FALSE(mbk::interpolate_base(samples, lin, ang, -0.1, m));
}

}  // namespace
