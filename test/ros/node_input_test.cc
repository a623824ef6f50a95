// NodeInput's models (mb_kinematics/ros/node_input.h), no master needed: without
// ~base_odometry the input and the kinematics read the loaded model itself (no copies: 8 MB saved
// at 10,000 bodies), also after a reload to another model; with it, the model split in two, and
// joint samples wait (bounded, in order) for the odometry after their stamp.
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
  const mbk::Model model = mbk_ros::load_node_model(params).model;
  EXPECT_EQ(model.body_count(), 29);
  double mass = 0;
  for (const mbk::Body& body : model.bodies) mass += body.mass;
  EXPECT_NEAR(mass, 70.0, 1e-12 * 70);
  EXPECT_TRUE(model.warnings.empty());
  EXPECT_NEAR(model.bodies[3].joint.offset.y(), -0.06, 1e-15);  // LeftUpLeg, in metres
}

// A quaternion of finite but huge components (1e200 times a unit one) gives its
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
  mbk::BaseOdometryBuffer::Fit fit;
  ASSERT_EQ(input.fill(0.2, model, joints, state, level, false, fit), "");
  const mbk::Body& base = model.bodies[1];
  const int e1 = base.q_index + mbk::first_euler_parameter(base.joint.type);
  EXPECT_NEAR(state.position[e1 + 2], q.z(), 1e-12);
  EXPECT_NEAR(state.position[e1 + 3], q.w(), 1e-12);
}

nav_msgs::Odometry odometry_at(double x) {  // the base at x on the x axis, moving at 1 m/s
  nav_msgs::Odometry o;
  o.header.frame_id = "odom";
  o.header.stamp = ros::Time(x);
  o.pose.pose.position.x = x;
  o.pose.pose.orientation.w = 1;
  o.twist.twist.linear.x = 1;
  return o;
}

mbk_ros::NodeInput::Ready joint_sample(const mbk::Model& model, double t) {
  sensor_msgs::JointStatePtr msg(new sensor_msgs::JointState);
  msg->header.stamp = ros::Time(t);
  msg->name = model.coordinate_names;
  msg->position.assign(model.nq, 0.1);
  return {msg, false};
}

// A sample waits for the odometry after its stamp (released by it, interpolated),
// at most ~base_odometry_wait (then held, or extrapolated when asked, and counted), in order.
class OdometryWait : public ::testing::TestWithParam<bool> {};

TEST_P(OdometryWait, ReleasedByTheLaterOdometryOrAfterTheWait) {
  using Fill = mbk_ros::NodeInput::Fill;
  using Problem = mbk_ros::InputProblem;
  mbk_ros::NodeParams params;
  params.base_odometry = "odom";
  params.acceleration_estimator = "backward_difference";
  params.base_odometry_extrapolate = GetParam();
  EXPECT_EQ(params.base_odometry_wait, 0.1) << "the documented default";
  mbk_ros::NodeInput input(params, "/odom");
  const mbk::Model chain = mbk_test::revolute_chain(2);
  input.load(chain);
  const int base_x = input.model().bodies[1].q_index;  // the base's free joint: x first
  input.add(odometry_at(1.0));
  const auto now = mbk_ros::NodeInput::Clock::now();
  const auto after = [&](double s) {
    return now + std::chrono::duration_cast<mbk_ros::NodeInput::Clock::duration>(
                     std::chrono::duration<double>(s));
  };
  mbk::Level level = mbk::Level::kPose;
  ros::Time stamp;
  for (const double t : {1.005, 1.012}) {  // both wait, in order
    ASSERT_TRUE(input.add(joint_sample(chain, t), t));
    ASSERT_EQ(input.fill(t, ros::Time(t), level, now), Fill::kWaiting);
  }
  EXPECT_EQ(input.release(after(0.05), stamp, level), Fill::kWaiting) << "within the wait";
  input.add(odometry_at(1.01));  // completes the first only
  ASSERT_EQ(input.release(after(0.05), stamp, level), Fill::kReady);
  EXPECT_EQ(stamp, ros::Time(1.005));
  EXPECT_NEAR(input.state().position[base_x], 1.005, 1e-12) << "interpolated";
  EXPECT_EQ(input.release(after(0.099), stamp, level), Fill::kWaiting) << "the second waits";
  ASSERT_EQ(input.release(after(0.1), stamp, level), Fill::kReady) << "its wait has ended";
  EXPECT_EQ(stamp, ros::Time(1.012));
  EXPECT_NEAR(input.state().position[base_x], GetParam() ? 1.012 : 1.01, 1e-12);
  EXPECT_FALSE(input.waiting());
  EXPECT_EQ(input.tally().problems(Problem::kBaseHeld), GetParam() ? 0 : 1);
  EXPECT_EQ(input.tally().problems(Problem::kBaseExtrapolated), GetParam() ? 1 : 0);
  EXPECT_NE(input.tally().last_problem().find(GetParam() ? "extrapolated" : "held"),
            std::string::npos)
      << input.tally().last_problem();
  ASSERT_TRUE(input.add(joint_sample(chain, 1.008), 1.008));  // covered already: not waiting
  EXPECT_EQ(input.fill(1.008, ros::Time(1.008), level, now), Fill::kReady);
}

INSTANTIATE_TEST_SUITE_P(HeldOrExtrapolated, OdometryWait, ::testing::Bool());

// More than ~queue_size samples waiting: the oldest goes on at once (held), none is lost.
TEST(OdometryQueue, BeyondTheQueueSizeTheOldestGoesOn) {
  using Fill = mbk_ros::NodeInput::Fill;
  mbk_ros::NodeParams params;
  params.base_odometry = "odom";
  params.acceleration_estimator = "backward_difference";
  params.queue_size = 2;
  mbk_ros::NodeInput input(params, "/odom");
  const mbk::Model chain = mbk_test::revolute_chain(2);
  input.load(chain);
  input.add(odometry_at(1.0));
  const auto now = mbk_ros::NodeInput::Clock::now();
  mbk::Level level = mbk::Level::kPose;
  ros::Time stamp;
  for (const double t : {1.02, 1.03, 1.04}) {
    ASSERT_TRUE(input.add(joint_sample(chain, t), t));
    ASSERT_EQ(input.fill(t, ros::Time(t), level, now), Fill::kWaiting);
  }
  ASSERT_EQ(input.release(now, stamp, level), Fill::kReady);
  EXPECT_EQ(stamp, ros::Time(1.02));
  EXPECT_EQ(input.release(now, stamp, level), Fill::kWaiting) << "two wait: within the size";
  input.add(odometry_at(1.05));
  for (const double t : {1.03, 1.04}) {
    ASSERT_EQ(input.release(now, stamp, level), Fill::kReady);
    EXPECT_EQ(stamp, ros::Time(t)) << "in order";
  }
  EXPECT_EQ(input.tally().problems(mbk_ros::InputProblem::kBaseHeld), 1);
}

}  // namespace
