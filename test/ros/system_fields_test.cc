// body_kinematics' system field (doc/node.md, system, messages/system.h) as the core
// computes it, and what it says when it cannot know the angular momentum: a body with mass but
// no inertia leaves angular_momentum_known false and angular_momentum zero (nothing invented),
// and a massless model leaves the field unfilled; missing_segments names the segments of the body
// that a .bvh ~model lacks, in every message. No ROS master: the fill function only.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/messages/body_kinematics.h"
#include "mb_kinematics/messages/system.h"
#include "mb_kinematics/ros/node_params.h"
#include "test/support/renamed_bvh.h"
#include "test/support/test_models.h"

namespace {

mbk::Vec3<double> vec(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }
mbk::Vec3<double> vec(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }

mb_kinematics_msgs::SystemKinematics filled(const mbk::Model& model, unsigned seed) {
  const mbk_test::Trajectory trajectory(model, seed);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, trajectory.at<double>(0.4), data, mbk::Level::kAcceleration);
  mb_kinematics_msgs::SystemKinematics msg;
  mbk_messages::fill_system_kinematics(model, data, msg);
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model, data, s);
  // Every field is the core's value, copied (float64 to float64: exact).
  EXPECT_EQ(msg.mass, s.mass);
  EXPECT_EQ(vec(msg.mass_center), s.mass_center);
  EXPECT_EQ(vec(msg.velocity), s.velocity);
  EXPECT_EQ(vec(msg.acceleration), s.acceleration);
  EXPECT_EQ(vec(msg.linear_momentum), s.linear_momentum);
  EXPECT_EQ(vec(msg.angular_momentum), s.angular_momentum);
  return msg;
}

// fill_kinematics' bodies (messages/body_kinematics.h): each body's vectors are Data's, the
// orientation Eigen's quaternion of its rotation, whatever their order in the message.
TEST(SystemFields, BodiesAreTheDataOfTheirIndex) {
  const mbk::Model model = mbk_test::random_tree(30, 7);
  const mbk_test::Trajectory trajectory(model, 7);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, trajectory.at<double>(0.6), data, mbk::Level::kAcceleration);
  mb_kinematics_msgs::BodyKinematicsArray msg;
  mbk_messages::init_body_kinematics(model, "world", msg);
  std::reverse(msg.bodies.begin(), msg.bodies.end());
  mbk_messages::fill_kinematics(ros::Time(3.0), model, data, true, msg);
  EXPECT_EQ(msg.header.stamp, ros::Time(3.0));
  for (const mb_kinematics_msgs::BodyKinematics& b : msg.bodies) {
    const int k = b.index;
    EXPECT_EQ(vec(b.pose.position), data.origin[k]) << k;
    EXPECT_EQ(vec(b.mass_center), data.mass_center[k]) << k;
    EXPECT_EQ(vec(b.twist.angular), data.omega[k]) << k;
    EXPECT_EQ(vec(b.twist.linear), data.mass_center_velocity[k]) << k;
    EXPECT_EQ(vec(b.accel.angular), data.alpha[k]) << k;
    EXPECT_EQ(vec(b.accel.linear), data.mass_center_acceleration[k]) << k;
    const Eigen::Quaterniond q(data.rotation[k]);
    const geometry_msgs::Quaternion& o = b.pose.orientation;
    EXPECT_TRUE(o.x == q.x() && o.y == q.y() && o.z == q.z() && o.w == q.w()) << k;
  }
}

TEST(SystemFields, AngularMomentumKnownWhenEveryBodyWithMassHasAnInertia) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(20, seed), seed);
    ASSERT_TRUE(mbk::inertias_known(model));
    const mb_kinematics_msgs::SystemKinematics msg = filled(model, seed);
    EXPECT_TRUE(msg.filled);
    EXPECT_GT(msg.mass, 0);
    EXPECT_TRUE(msg.angular_momentum_known);
    EXPECT_GT(vec(msg.angular_momentum).norm(), 0);  // a moving tree: not zeros
  }
}

TEST(SystemFields, AngularMomentumLeftOutWithoutAnInertia) {
  mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(20, 4), 4);
  int k = 1;
  while (!(model.bodies[k].mass > 0)) ++k;
  model.bodies[k].has_inertia = false;  // one body with mass lacks its inertia
  ASSERT_EQ(mbk::bodies_without_inertia(model), std::vector<std::string>{model.bodies[k].name});
  const mb_kinematics_msgs::SystemKinematics msg = filled(model, 4);
  EXPECT_TRUE(msg.filled);  // the rest is known
  EXPECT_GT(vec(msg.velocity).norm(), 0);
  EXPECT_FALSE(msg.angular_momentum_known);
  EXPECT_EQ(vec(msg.angular_momentum), mbk::Vec3<double>::Zero());
}

TEST(SystemFields, NotFilledWithoutMass) {
  mbk::Model model = mbk_test::random_tree(10, 5);
  for (int k = 1; k <= model.body_count(); ++k) model.bodies[k].mass = 0;
  const mb_kinematics_msgs::SystemKinematics msg = filled(model, 5);
  EXPECT_FALSE(msg.filled);
  EXPECT_FALSE(msg.angular_momentum_known);
}

// test/io/data/cmu_walk.bvh with paws for hands, written to a file of the test's own.
std::string skeleton_without_hands() {
  const std::string path = ::testing::TempDir() + "system_fields_paws.bvh";
  std::ofstream(path) << mbk_test::renamed(mbk_test::source_path("test/io/data/cmu_walk.bvh"),
                                           {{"LeftHand", "LeftPaw"}, {"RightHand", "RightPaw"}});
  return path;
}

// The node's ~model a skeleton without hands: every body_kinematics message names the segments
// whose mass the others carry, also those filled over a subset of the bodies and those after.
TEST(SystemFields, TheSegmentsAModelLacksAreInEveryMessage) {
  mbk_ros::NodeParams p;
  p.model = skeleton_without_hands();
  p.bvh = {0.01, 70, "male", ""};
  const mbk::ModelFile loaded = mbk_ros::load_node_model(p);
  const mbk::Model& model = loaded.model;
  const std::vector<std::string> hands = {"left hand", "right hand"};
  ASSERT_EQ(loaded.missing_segments, hands);
  mb_kinematics_msgs::BodyKinematicsArray msg;
  mbk_messages::init_body_kinematics(model, "R", msg, loaded.missing_segments);
  const mbk_test::Trajectory trajectory(model, 7);
  mbk::Data<double> data(model);
  for (const bool complete : {true, false, true}) {
    mbk::forward_kinematics(model, trajectory.at<double>(0.4), data, mbk::Level::kAcceleration);
    mbk_messages::fill_kinematics(ros::Time(1), model, data, complete, msg);
    EXPECT_EQ(msg.system.filled, complete);
    EXPECT_EQ(msg.system.missing_segments, hands);
  }
  EXPECT_NEAR(msg.system.mass, 70, 1e-9);
}

// Every segment found, or no anthropometric table: none named.
TEST(SystemFields, NoSegmentMissingFromAWholeSkeletonOrARobot) {
  mbk_ros::NodeParams p;
  p.model = mbk_test::source_path("test/io/data/cmu_walk.bvh");
  p.bvh = {0.01, 70, "male", ""};
  EXPECT_TRUE(mbk_ros::load_node_model(p).missing_segments.empty());
  p.model = skeleton_without_hands();
  p.bvh.body_mass = 0;  // massless segments: no table
  EXPECT_TRUE(mbk_ros::load_node_model(p).missing_segments.empty());
  p.bvh.body_mass = 70;
  p.lower_body_array = {0, 1};  // wins over ~model
  EXPECT_TRUE(mbk_ros::load_node_model(p).missing_segments.empty());
  p.lower_body_array.clear();
  p.model = mbk_test::source_path("config/human_body.urdf");
  EXPECT_TRUE(mbk_ros::load_node_model(p).missing_segments.empty());
}

}  // namespace
