// mb_kinematics_node (system.test): body_kinematics carries the whole system as the
// core computes it for the same state, and ~get_partial_velocities returns the partial velocity
// arrays of the latest sample, sparse, keyed by independent speed (finger mimics arm2_joint).
#include <mb_kinematics_msgs/GetPartialVelocities.h>

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;  // as node_test.cc: values pass through float64 messages exactly,
                               // the two formulations differ by rounding only
const double kDt = 0.02;

class SystemTest : public ::testing::Test {
 protected:
  void SetUp() override {
    states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 100);
    connect(states_, recorder_);
  }
  // Samples i = 0..n-1 of `trajectory` (with velocities) at start + i dt; waits for the last.
  void publish_run(const Quadratic& trajectory, const ros::Time& start, int n) {
    for (int i = 0; i < n; ++i) {
      states_.publish(
          joint_state_msg(model_, trajectory.at(i * kDt), start + ros::Duration(i * kDt), true));
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  }

  ros::NodeHandle nh_;
  mbk::Model model_ = test_model();
  ros::Publisher states_;
  KinematicsRecorder recorder_{nh_, "body_kinematics"};
};

TEST_F(SystemTest, SystemQuantitiesOnBodyKinematics) {
  const Quadratic trajectory(model_, 0.7);
  const ros::Time start(400.0);
  publish_run(trajectory, start, 3);
  const auto msgs = recorder_.at(start + ros::Duration(2 * kDt));
  ASSERT_EQ(msgs.size(), 1u);
  const mb_kinematics_msgs::SystemKinematics& got = msgs[0].system;
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model_, expected_kinematics(model_, trajectory.at(2 * kDt)), s);
  EXPECT_TRUE(got.filled);
  EXPECT_DOUBLE_EQ(got.mass, 4.3);          // test_robot.urdf's masses
  EXPECT_TRUE(got.angular_momentum_known);  // every link with mass has an <inertia>
  ASSERT_TRUE(s.angular_momentum_known);
  expect_near(vec(got.mass_center), s.mass_center, kTol, "p_G");
  expect_near(vec(got.velocity), s.velocity, kTol, "v_G");
  expect_near(vec(got.acceleration), s.acceleration, kTol, "a_G");
  expect_near(vec(got.linear_momentum), s.linear_momentum, kTol, "M v_G");
  expect_near(vec(got.angular_momentum), s.angular_momentum, kTol, "H_G");
  EXPECT_GT(s.angular_momentum.norm(), 0.1);  // a moving robot, not zeros
  EXPECT_GT(s.acceleration.norm(), 0.01);
}

TEST_F(SystemTest, PartialVelocitiesServiceAtTheLatestSample) {
  ros::ServiceClient client = nh_.serviceClient<mb_kinematics_msgs::GetPartialVelocities>(
      "mb_kinematics/get_partial_velocities");
  ASSERT_TRUE(client.waitForExistence(ros::Duration(10)));
  const Quadratic trajectory(model_, 2.3);
  const ros::Time start(500.0);
  publish_run(trajectory, start, 3);
  mb_kinematics_msgs::GetPartialVelocities srv;
  srv.request.bodies = {"finger", "arm2", "camera"};
  ASSERT_TRUE(client.call(srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_EQ(srv.response.header.stamp, start + ros::Duration(2 * kDt));
  EXPECT_EQ(srv.response.header.frame_id, "base_link");
  ASSERT_EQ(srv.response.partials.size(), 3u);

  const mbk::JointState<double> state = trajectory.at(2 * kDt);
  mbk::PartialVelocities<double> pv(model_);
  mbk::Data<double> data(model_);
  mbk::partial_velocity_kinematics(model_, state, pv, data);
  for (const auto& got : srv.response.partials) {
    SCOPED_TRACE(got.body);
    const int k = model_.body_index(got.body);
    ASSERT_GT(k, 0);
    const std::vector<mbk::SpeedColumn> columns = mbk::independent_columns(model_, pv, k);
    ASSERT_EQ(got.speeds.size(), columns.size());
    ASSERT_EQ(got.partial_omega.size(), columns.size());
    ASSERT_EQ(got.partial_velocity.size(), columns.size());
    ASSERT_EQ(got.partial_omega_dot.size(), columns.size());
    ASSERT_EQ(got.partial_velocity_dot.size(), columns.size());
    mbk::Vec3<double> v = mbk::Vec3<double>::Zero();
    for (size_t i = 0; i < columns.size(); ++i) {
      EXPECT_EQ(got.speeds[i], model_.speed_names[columns[i].speed]);
      EXPECT_NE(got.speeds[i], "finger_joint");  // the mimic has no column of its own
      expect_near(vec(got.partial_omega[i]), columns[i].omega, kTol, "omega_kr");
      expect_near(vec(got.partial_velocity[i]), columns[i].velocity, kTol, "v_kr");
      expect_near(vec(got.partial_omega_dot[i]), columns[i].omega_dot, kTol, "omega_kr'");
      expect_near(vec(got.partial_velocity_dot[i]), columns[i].velocity_dot, kTol, "v_kr'");
      v += vec(got.partial_velocity[i]) * state.velocity[columns[i].speed];
    }
    // v_k = sum_r v_kr y_r, against the body's velocity on body_kinematics at the same stamp.
    const auto msgs = recorder_.at(srv.response.header.stamp);
    ASSERT_EQ(msgs.size(), 1u);
    expect_near(v, vec(msgs[0].bodies[k - 1].twist.linear), kTol, "sum of v_kr y_r");
  }
  EXPECT_TRUE(srv.response.partials[2].speeds.empty());  // camera: fixed to R

  srv.request.bodies = {"arm2", "no_such_link"};
  ASSERT_TRUE(client.call(srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("'no_such_link'"), std::string::npos) << srv.response.message;
  EXPECT_TRUE(srv.response.partials.empty());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "system_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
