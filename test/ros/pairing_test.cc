// joint_accelerations: used for the joint_states sample with the same stamp, whichever of the
// two arrives first (pairing.test). The accelerations are arbitrary (not the trajectory's), so
// only pairing can give the expected values, and from the first sample on.
#include <mb_kinematics_msgs/JointAccelerations.h>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;

class PairingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 100);
    accelerations_ =
        nh_.advertise<mb_kinematics_msgs::JointAccelerations>("joint_accelerations", 100);
    connect(states_, recorder_);
    ASSERT_TRUE(wait_until([&] { return accelerations_.getNumSubscribers() > 0; }, 10));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  // The trajectory's state at tau with accelerations 3 sin(5 i + tau) instead of its own.
  mbk::JointState<double> state(double tau) const {
    mbk::JointState<double> s = trajectory_.at(tau);
    for (int i = 0; i < model_.nq; ++i) s.acceleration[i] = 3 * std::sin(5 * i + tau);
    mbk::apply_mimics(model_, s);
    return s;
  }
  mb_kinematics_msgs::JointAccelerations accelerations_msg(const mbk::JointState<double>& s,
                                                           const ros::Time& stamp) const {
    const sensor_msgs::JointState js = joint_state_msg(model_, s, stamp, false);
    mb_kinematics_msgs::JointAccelerations msg;
    msg.header.stamp = stamp;
    msg.name = js.name;
    for (const std::string& n : js.name)
      msg.acceleration.push_back(s.acceleration[model_.coordinate_index(n)]);
    return msg;
  }
  void expect_sample(const ros::Time& stamp, const mbk::JointState<double>& s) {
    ASSERT_TRUE(recorder_.wait_for(stamp));
    const auto msgs = recorder_.at(stamp);
    ASSERT_EQ(msgs.size(), 1u);
    expect_kinematics(msgs[0], model_, expected_kinematics(model_, s), kTol);
  }

  ros::NodeHandle nh_;
  mbk::Model model_ = test_model();
  Quadratic trajectory_{model_};
  ros::Publisher states_, accelerations_;
  KinematicsRecorder recorder_{nh_, "body_kinematics"};
};

TEST_F(PairingTest, AccelerationsBeforeJointStates) {
  const mbk::JointState<double> s = state(0.1);
  const ros::Time stamp(10.0);
  accelerations_.publish(accelerations_msg(s, stamp));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  states_.publish(joint_state_msg(model_, s, stamp, true));
  expect_sample(stamp, s);
}

TEST_F(PairingTest, JointStatesBeforeAccelerations) {
  const mbk::JointState<double> s = state(0.2);
  const ros::Time stamp(20.0);
  states_.publish(joint_state_msg(model_, s, stamp, true));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_TRUE(recorder_.at(stamp).empty()) << "did not wait for the accelerations";
  accelerations_.publish(accelerations_msg(s, stamp));
  expect_sample(stamp, s);
}

// A sample whose accelerations never come is computed with estimates when the next arrives.
TEST_F(PairingTest, UnpairedSampleIsEstimated) {
  const double dt = 0.02;
  const ros::Time start(30.0);
  for (int i = 0; i < 3; ++i) {
    const mbk::JointState<double> s = state(i * dt);
    const ros::Time stamp = start + ros::Duration(i * dt);
    if (i != 1) accelerations_.publish(accelerations_msg(s, stamp));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    states_.publish(joint_state_msg(model_, s, stamp, true));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  expect_sample(start, state(0));
  expect_sample(start + ros::Duration(2 * dt), state(2 * dt));
  // Sample 1: accelerations from the given velocities (two samples: the line through them),
  // which for the quadratic trajectory are its own, exactly.
  expect_sample(start + ros::Duration(dt), trajectory_.at(dt));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "pairing_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
