// NodeInput's models (mb_kinematics/ros/node_input.h), no master needed: without
// ~base_odometry the input and the kinematics read the loaded model itself (no copies: 8 MB saved
// at 10,000 bodies), also after a reload to another model; with it, the model split in two.
#include "mb_kinematics/ros/node_input.h"

#include <gtest/gtest.h>

#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/ros/base_odometry_input.h"
#include "mb_kinematics/ros/node_params.h"
#include "test/support/test_models.h"

namespace {

TEST(NodeInput, WithoutBaseOdometryEveryModelIsTheLoadedOne) {
  const mbk_ros::NodeParams params;
  mbk_ros::NodeInput input(params, "");
  for (const int n : {12, 30}) {  // at start, then ~reload to another model
    input.load(mbk_test::random_tree(n, 1));
    EXPECT_EQ(&input.model(), &input.loaded());
    EXPECT_EQ(input.model().body_count(), n);
    EXPECT_EQ(input.state().position.size(), input.model().nq);
  }
}

TEST(NodeInput, WithBaseOdometryTheKinematicsModelHasTheBase) {
  mbk_ros::NodeParams params;
  params.base_odometry = "odom";
  mbk_ros::NodeInput input(params, "/odom");
  for (const int n : {12, 30}) {  // chains of revolute joints: no floating root of their own
    input.load(mbk_test::revolute_chain(n));
    EXPECT_NE(&input.model(), &input.loaded());
    EXPECT_EQ(input.loaded().body_count(), n);
    EXPECT_EQ(input.model().body_count(), n + 1);  // the base on its free joint first
    EXPECT_EQ(input.state().position.size(), input.model().nq);
  }
}

// ~model may be a BVH file, with ~scale, ~body_mass and ~sex for its skeleton.
TEST(NodeParams, ABvhModelTakesItsScaleAndBodyMass) {
  mbk_ros::NodeParams params;
  params.model = mbk_test::source_path("test/io/data/cmu_walk.bvh");
  params.bvh = {0.01, 70.0, "female"};
  const mbk::Model model = mbk_ros::load_node_model(params);
  EXPECT_EQ(model.body_count(), 29);
  double mass = 0;
  for (const mbk::Body& body : model.bodies) mass += body.mass;
  EXPECT_NEAR(mass, 70.0, 1e-12 * 70);
  EXPECT_TRUE(model.warnings.empty());
  EXPECT_NEAR(model.bodies[3].joint.offset.y(), -0.06, 1e-15);  // LeftUpLeg, in metres
}

// Issue 24.9: a quaternion of finite but huge components (1e200 times a unit one) gives its
// rotation to the base, not the identity its overflowing norm made of it.
TEST(BaseOdometryInput, HugeQuaternionIsItsRotation) {
  const auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk_ros::BaseOdometryInput input(*estimator, 1.0, "/odom");
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  nav_msgs::Odometry o;
  o.header.frame_id = "odom";
  o.pose.pose.orientation.z = 1e200 * q.z();
  o.pose.pose.orientation.w = 1e200 * q.w();
  for (const double t : {0.0, 0.1, 0.2, 0.3}) EXPECT_EQ(input.add(o, t), "");
  mbk::Model in, model;
  mbk_ros::BaseOdometryInput::split(mbk_test::revolute_chain(2), in, model);
  mbk::JointState<double> joints(in), state(model);
  mbk::Level level = mbk::Level::kAcceleration;
  ASSERT_EQ(input.fill(0.2, model, joints, state, level), "");
  const mbk::Body& base = model.bodies[1];
  const int e1 = base.q_index + mbk::first_euler_parameter(base.joint.type);
  EXPECT_NEAR(state.position[e1 + 2], q.z(), 1e-12);
  EXPECT_NEAR(state.position[e1 + 3], q.w(), 1e-12);
}

}  // namespace
