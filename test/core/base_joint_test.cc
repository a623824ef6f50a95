// The floating base as a free joint (core/base_joint.h): the coordinates of a free joint put its
// body where the motion says (checked through forward_kinematics), and with_floating_base adds
// a base without changing the rest; body_kinematics of the base-carrying model equals the
// kinematics carried into R by apply_floating_base (what mbk bag does).
#include "mb_kinematics/core/base_joint.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"
#include "test/support/test_models.h"
#include "test/support/urdf_facts.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;
constexpr double kTol = 1e-12;

mbk::BaseMotion some_motion() {
  mbk::BaseMotion m;
  m.position = V(1.5, -0.4, 0.9);
  m.rotation = mbk::rotation_123(0.4, -0.7, 2.1);
  m.velocity = V(0.3, -1.2, 0.5);
  m.omega = V(-0.8, 0.6, 1.1);
  m.acceleration = V(2.0, 0.1, -0.7);
  m.alpha = V(0.5, -1.5, 0.2);
  return m;
}

// A one-body model on a free joint of `type` with an offset and an offset rotation.
mbk::Model one_free_body(mbk::JointType type) {
  mbk::Model model;
  model.bodies.resize(2);
  model.bodies[1].name = "base";
  model.bodies[1].joint.name = "root";
  model.bodies[1].joint.type = type;
  model.bodies[1].joint.offset = V(0.1, 0.2, -0.3);
  model.bodies[1].joint.rotation = mbk::rotation_123(0.3, 0.2, -0.5);
  mbk::finalize_model(model);
  return model;
}

void expect_near(const V& a, const V& b, double tol, const char* what) {
  EXPECT_LT((a - b).norm(), tol) << what << ": " << a.transpose() << " vs " << b.transpose();
}

TEST(BaseJoint, FreeJointCoordinatesReproduceTheMotion) {
  for (mbk::JointType type : {mbk::JointType::kFreeEuler, mbk::JointType::kFree123}) {
    const mbk::Model model = one_free_body(type);
    const mbk::BaseMotion m = some_motion();
    mbk::JointState<double> s(model);
    ASSERT_EQ(mbk::free_joint_coordinates(model.bodies[1].joint, m, s.position.data(),
                                          s.velocity.data(), s.acceleration.data()),
              "");
    mbk::Data<double> d(model);
    mbk::forward_kinematics(model, s, d);
    EXPECT_LT((d.rotation[1] - m.rotation).norm(), kTol);
    expect_near(d.origin[1], m.position, kTol, "position");
    expect_near(d.origin_velocity[1], m.velocity, kTol, "velocity");
    expect_near(d.omega[1], m.omega, kTol, "omega");
    expect_near(d.origin_acceleration[1], m.acceleration, kTol, "acceleration");
    expect_near(d.alpha[1], m.alpha, kTol, "alpha");
  }
}

// free_123 in every Euler order; the proper Euler orders' gimbal lock is at beta = 0.
TEST(BaseJoint, FreeJointCoordinatesInEveryEulerOrder) {
  for (int i = 0; i <= static_cast<int>(mbk::EulerOrder::kLast); ++i) {
    mbk::Model model = one_free_body(mbk::JointType::kFree123);
    mbk::Joint& joint = model.bodies[1].joint;
    joint.euler_order = static_cast<mbk::EulerOrder>(i);
    mbk::finalize_model(model);
    const mbk::BaseMotion m = some_motion();
    mbk::JointState<double> s(model);
    ASSERT_EQ(mbk::free_joint_coordinates(joint, m, s.position.data(), s.velocity.data(),
                                          s.acceleration.data()),
              "")
        << mbk::to_string(joint.euler_order);
    mbk::Data<double> d(model);
    mbk::forward_kinematics(model, s, d);
    EXPECT_LT((d.rotation[1] - m.rotation).norm(), kTol) << mbk::to_string(joint.euler_order);
    expect_near(d.omega[1], m.omega, kTol, "omega");
    expect_near(d.alpha[1], m.alpha, kTol, "alpha");
    mbk::BaseMotion locked = m;
    const std::array<int, 3> a = mbk::euler_axes(joint.euler_order);
    const double beta = mbk::is_tait_bryan(joint.euler_order) ? M_PI / 2 : 0.0;
    locked.rotation = joint.rotation * Eigen::AngleAxisd(0.3, V::Unit(a[0])) *
                      Eigen::AngleAxisd(beta, V::Unit(a[1])) *
                      Eigen::AngleAxisd(0.2, V::Unit(a[2]));
    double q[6], qd[6];
    const std::string error = mbk::free_joint_coordinates(joint, locked, q, qd, nullptr);
    EXPECT_NE(error.find("gimbal lock of the " + mbk::to_string(joint.euler_order)),
              std::string::npos)
        << error;
  }
}

TEST(BaseJoint, RefusesWhatItCannotConvert) {
  const mbk::Model model = one_free_body(mbk::JointType::kFree123);
  mbk::BaseMotion m = some_motion();
  m.rotation = model.bodies[1].joint.rotation * mbk::rotation_123(0.2, M_PI / 2, 0.1);
  double q[7], qd[7], qdd[7];
  EXPECT_NE(mbk::free_joint_coordinates(model.bodies[1].joint, m, q, qd, qdd).find("gimbal"),
            std::string::npos);
  mbk::Joint revolute;
  revolute.type = mbk::JointType::kRevolute;
  EXPECT_NE(mbk::free_joint_coordinates(revolute, m, q, qd, qdd), "");
}

TEST(BaseJoint, WithFloatingBaseMovesTheWholeModel) {
  const mbk::Model fixed = mbk::load_urdf_file(mbk_test::source_path("test/ros/test_robot.urdf"));
  EXPECT_FALSE(mbk::has_floating_root(fixed));
  const mbk::Model floating = mbk::with_floating_base(fixed, "odom", "base");
  EXPECT_TRUE(mbk::has_floating_root(floating));
  ASSERT_EQ(floating.body_count(), fixed.body_count() + 1);
  ASSERT_EQ(floating.nq, fixed.nq + 7);
  EXPECT_EQ(floating.bodies[1].name, "base_link");
  EXPECT_EQ(floating.frame, "odom");
  EXPECT_EQ(floating.coordinate_names[6], "base/e4");
  for (int k = 1; k <= fixed.body_count(); ++k) {
    EXPECT_EQ(floating.bodies[k + 1].name, fixed.bodies[k].name);
    EXPECT_EQ(floating.bodies[k + 1].lower, fixed.bodies[k].lower + 1);
  }
  const mbk::Model stripped = mbk::without_root_body(floating);
  EXPECT_EQ(stripped.frame, "base_link");
  EXPECT_EQ(stripped.coordinate_names, fixed.coordinate_names);
  EXPECT_EQ(stripped.lower_body_array(), fixed.lower_body_array());
  ASSERT_EQ(stripped.mimics.size(), fixed.mimics.size());
  EXPECT_EQ(stripped.mimics[0].source, fixed.mimics[0].source);
  // The fixed model's state with the base at `m`: every body moved rigidly by the base's pose.
  mbk::JointState<double> s(fixed), sf(floating);
  for (int i = 0; i < fixed.nq; ++i) s.position[i] = 0.1 * i - 0.3;
  mbk::apply_mimics(fixed, s);
  const mbk::BaseMotion m = some_motion();
  ASSERT_EQ(mbk::free_joint_coordinates(floating.bodies[1].joint, m, sf.position.data(),
                                        sf.velocity.data(), sf.acceleration.data()),
            "");
  sf.position.tail(fixed.nq) = s.position;
  mbk::apply_mimics(floating, sf);
  EXPECT_LT((sf.position.tail(fixed.nq) - s.position).norm(), kTol) << "mimics shifted";
  mbk::Data<double> d(fixed), df(floating);
  mbk::forward_kinematics(fixed, s, d, mbk::Level::kPose);
  mbk::forward_kinematics(floating, sf, df, mbk::Level::kPose);
  for (int k = 1; k <= fixed.body_count(); ++k) {
    expect_near(df.origin[k + 1], m.position + m.rotation * d.origin[k], kTol, "origin");
    EXPECT_LT((df.rotation[k + 1] - m.rotation * d.rotation[k]).norm(), kTol);
  }
}

// The node's way (the base as a free joint, with_floating_base) and mbk bag's way (the
// kinematics in the root frame carried into R, apply_floating_base) agree on every body and
// quantity: omega, alpha and the mass centers' p, v, a include the base's motion.
TEST(BaseJoint, AgreesWithCarryingIntoR) {
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/human_body.yaml"));
  const mbk::Model based = mbk::with_floating_base(model, "odom", "base");
  const mbk_test::Trajectory trajectory(model, 3);
  const mbk::JointState<double> s = trajectory.at<double>(0.41);
  const mbk::BaseMotion m = some_motion();
  mbk::JointState<double> sb(based);
  ASSERT_EQ(mbk::free_joint_coordinates(based.bodies[1].joint, m, sb.position.data(),
                                        sb.velocity.data(), sb.acceleration.data()),
            "");
  sb.position.tail(model.nq) = s.position;
  sb.velocity.tail(model.nq) = s.velocity;
  sb.acceleration.tail(model.nq) = s.acceleration;
  mbk::Data<double> carried(model), direct(based);
  mbk::forward_kinematics(model, s, carried, mbk::Level::kAcceleration);
  mbk::apply_floating_base(m, carried);
  mbk::forward_kinematics(based, sb, direct, mbk::Level::kAcceleration);
  const double tol = 1e-11;
  for (int k = 1; k <= model.body_count(); ++k) {
    SCOPED_TRACE(model.bodies[k].name);
    EXPECT_LT((direct.rotation[k + 1] - carried.rotation[k]).norm(), tol);
    expect_near(direct.omega[k + 1], carried.omega[k], tol, "omega");
    expect_near(direct.alpha[k + 1], carried.alpha[k], tol, "alpha");
    expect_near(direct.mass_center[k + 1], carried.mass_center[k], tol, "p");
    expect_near(direct.mass_center_velocity[k + 1], carried.mass_center_velocity[k], tol, "v");
    expect_near(direct.mass_center_acceleration[k + 1], carried.mass_center_acceleration[k], tol,
                "a");
  }
}

// The root link: with a floating base it is the base body, with its link's mass, mass
// center and inertia, and the system moves with it; the node's way and mbk bag's way agree.
TEST(BaseJoint, FloatingBaseCarriesTheRootLinksMass) {
  const mbk::Model model = mbk::load_urdf_string(mbk_test::kHeavyRootUrdf, "q.urdf");
  const mbk::Model based = mbk::with_floating_base(model, "odom", "base");
  const mbk::Body& base = based.bodies[1];
  EXPECT_EQ(base.name, "base");
  EXPECT_EQ(base.mass, 15.36);
  EXPECT_EQ(base.mass_center, V(0.1, -0.02, 0.05));
  ASSERT_TRUE(base.has_inertia);
  EXPECT_EQ(base.inertia, M(V(0.3, 0.4, 0.5).asDiagonal()));
  EXPECT_EQ(based.bodies[0].mass, 0.0);  // R (the odometry frame) has none
  mbk::JointState<double> s(model), sb(based);
  s.position[0] = 0.4;
  s.velocity[0] = 1.3;
  s.acceleration[0] = -0.7;
  const mbk::BaseMotion m = some_motion();
  ASSERT_EQ(mbk::free_joint_coordinates(base.joint, m, sb.position.data(), sb.velocity.data(),
                                        sb.acceleration.data()),
            "");
  sb.position.tail(1) = s.position;
  sb.velocity.tail(1) = s.velocity;
  sb.acceleration.tail(1) = s.acceleration;
  mbk::Data<double> carried(model), direct(based);
  mbk::forward_kinematics(model, s, carried, mbk::Level::kAcceleration);
  mbk::apply_floating_base(m, carried);
  mbk::forward_kinematics(based, sb, direct, mbk::Level::kAcceleration);
  mbk::SystemKinematics<double> a, b;
  mbk::system_kinematics(model, carried, a);
  mbk::system_kinematics(based, direct, b);
  EXPECT_EQ(a.mass, 15.36 + 2.5);
  EXPECT_EQ(b.mass, 15.36 + 2.5);
  expect_near(direct.mass_center[1], m.position + m.rotation * V(0.1, -0.02, 0.05), 1e-15, "p_b");
  const double tol = 1e-12;
  expect_near(a.mass_center, b.mass_center, tol, "p_G");
  expect_near(a.velocity, b.velocity, tol, "v_G");
  expect_near(a.acceleration, b.acceleration, tol, "a_G");
  ASSERT_TRUE(a.angular_momentum_known && b.angular_momentum_known);
  expect_near(a.angular_momentum, b.angular_momentum, tol, "H_G");
}

}  // namespace
