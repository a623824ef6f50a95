// No allocation per sample in the node's output fill functions (doc/node.md): once the
// messages are made (names and frames set), filling tf, body_kinematics and its system field
// allocates nothing; nor does pairing joint_accelerations on the input side. No ROS master: the
// fill functions only (the publishers reuse the filled messages, outputs/reused_message.h).
#include <gtest/gtest.h>

#include <boost/make_shared.hpp>
#include <string>
#include <vector>

#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/messages/body_kinematics.h"
#include "mb_kinematics/messages/system.h"
#include "mb_kinematics/ros/joint_state_input.h"
#include "mb_kinematics/ros/outputs/tf_output.h"
#include "test/support/allocation_counter.h"
#include "test/support/test_models.h"

namespace {

using mbk_test::allocation_counts;
using mbk_test::AllocationCounts;

// Frame names longer than any small-string buffer, so that copying one would allocate.
std::string frame(int k) { return "a_frame_name_longer_than_small_strings_" + std::to_string(k); }

// `after` is taken before `what` is built (building it allocates).
void expect_none(const AllocationCounts& before, const AllocationCounts& after,
                 const std::string& what) {
  EXPECT_EQ(after.news, before.news) << what << ": operator new per sample";
  EXPECT_EQ(after.mallocs, before.mallocs) << what << ": malloc per sample";
}

// The counters see what the tests look for (a string copy, a vector), so the tests can fail.
TEST(OutputAllocation, CountersSeeStringsAndVectors) {
  const AllocationCounts before = allocation_counts();
  std::vector<std::string> copy(1, frame(1));
  asm volatile("" : : "g"(copy.data()) : "memory");
  EXPECT_GE(allocation_counts().news, before.news + 2);
}

TEST(OutputAllocation, NoneInFillTransforms) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = mbk_test::random_tree(100, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    std::vector<mbk_messages::TfJoint> moving;
    for (int k = 1; k <= model.body_count(); ++k)
      if (mbk::coordinate_count(model.bodies[k].joint.type) > 0)
        moving.push_back(mbk_messages::tf_joint(model, k));
    std::vector<geometry_msgs::TransformStamped> transforms(moving.size());
    for (size_t i = 0; i < moving.size(); ++i) {
      transforms[i].header.frame_id = frame(model.bodies[moving[i].body].lower);
      transforms[i].child_frame_id = frame(moving[i].body);
    }
    const std::vector<mbk::JointState<double>> states = {trajectory.at<double>(0.1),
                                                         trajectory.at<double>(0.2)};
    const AllocationCounts before = allocation_counts();
    for (int sample = 0; sample < 4; ++sample)
      mbk_messages::fill_transforms(model, states[sample % 2], moving, ros::Time(1.0 + sample),
                                    transforms);
    const AllocationCounts after = allocation_counts();
    expect_none(before, after, "fill_transforms, seed " + std::to_string(seed));
    // The fill did its work: the last sample's stamp and frames as set.
    ASSERT_FALSE(transforms.empty());
    EXPECT_EQ(transforms.back().header.stamp, ros::Time(4.0));
    EXPECT_EQ(transforms.back().child_frame_id, frame(moving.back().body));
  }
}

TEST(OutputAllocation, NoneInFillBodyKinematicsAndSystem) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = mbk_test::random_tree(100, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    mbk::Data<double> data(model);
    mbk::forward_kinematics(model, trajectory.at<double>(0.3), data, mbk::Level::kAcceleration);
    mb_kinematics_msgs::BodyKinematicsArray msg;
    mbk_messages::init_body_kinematics(model, frame(0), msg);
    const AllocationCounts before = allocation_counts();
    for (int sample = 0; sample < 4; ++sample) {
      mbk_messages::fill_kinematics(ros::Time(1.0 + sample), model, data, true, msg);
    }
    const AllocationCounts after = allocation_counts();
    expect_none(before, after,
                "fill_body_kinematics and fill_system_kinematics, seed " + std::to_string(seed));
    ASSERT_EQ(msg.bodies.size(), static_cast<size_t>(model.body_count()));
    EXPECT_EQ(msg.bodies.back().pose.position.x, data.origin[model.body_count()].x());
    EXPECT_EQ(msg.header.stamp, ros::Time(4.0));
  }
}

// The input side's joint_accelerations path: once the pairing keeps its most messages (16), a
// message converted, kept and paired with its joint_states sample allocates nothing (the
// pairing swaps the oldest kept message's storage in; the names are looked up once per list).
TEST(OutputAllocation, NoneInPairingAccelerations) {
  const mbk::Model model = mbk_test::random_tree(100, 1);
  mbk_ros::JointStateInput input(model, *mbk::make_derivative_estimator("kalman_smooth"));
  std::vector<sensor_msgs::JointStateConstPtr> samples;
  std::vector<mb_kinematics_msgs::JointAccelerations> accelerations(40);
  for (int i = 0; i < 40; ++i) {
    auto js = boost::make_shared<sensor_msgs::JointState>();
    js->header.stamp = ros::Time(1.0 + i);
    js->name = model.coordinate_names;
    js->position.assign(model.nq, 0.1 * i);
    samples.push_back(js);
    accelerations[i].header.stamp = js->header.stamp;
    accelerations[i].name = model.coordinate_names;
    accelerations[i].acceleration.assign(model.nq, 0.5);
  }
  std::string error;
  auto run = [&](int i) {  // the sample first, waiting; then its accelerations complete it
    const bool waits = input.pair(samples[i], true).empty();
    const auto& ready = input.pair(accelerations[i], 1.0 + i, error);
    return waits && error.empty() && ready.size() == 1 && ready[0].sample == samples[i] &&
           input.paired(1.0 + i) != nullptr;
  };
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(run(i)) << i << ": " << error;
  const AllocationCounts before = allocation_counts();
  bool paired = true;
  for (int i = 20; i < 40; ++i) paired = run(i) && paired;
  const AllocationCounts after = allocation_counts();
  expect_none(before, after, "pairing joint_accelerations");
  EXPECT_TRUE(paired);
  ASSERT_NE(input.paired(40.0), nullptr);
  EXPECT_EQ(input.paired(40.0)->value[3], 0.5);
  EXPECT_NE(input.paired(25.0), nullptr);  // the 16 latest stamps (25 to 40) are kept
  EXPECT_EQ(input.paired(24.0), nullptr);
}

}  // namespace
