// ~frame_prefix (frame_prefix.test): two nodes on one URDF with prefixes r1/ and r2/. Every
// frame each puts on /tf and /tf_static carries its prefix (so none collides), R is prefixed
// too (it is the URDF's root link), composed lookups give the core's poses, and body names in
// body_kinematics and lower_body_array stay the model's.
#include <geometry_msgs/TwistStamped.h>
#include <mb_kinematics_msgs/LowerBodyArray.h>
#include <ros/master.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/transform_listener.h>

#include <mutex>
#include <set>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;
const double kDt = 0.02;

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

TEST(FramePrefixTest, NoFrameCollides) {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::set<std::string> frames;  // parent and child frames seen on /tf and /tf_static
  auto on_tf = [&](const tf2_msgs::TFMessage::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& t : m->transforms) {
      frames.insert(t.header.frame_id);
      frames.insert(t.child_frame_id);
    }
  };
  ros::Subscriber tf = nh.subscribe<tf2_msgs::TFMessage>("/tf", 100, on_tf);
  ros::Subscriber tf_static = nh.subscribe<tf2_msgs::TFMessage>("/tf_static", 100, on_tf);
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  geometry_msgs::TwistStamped twist;
  ros::Subscriber twist_sub = nh.subscribe<geometry_msgs::TwistStamped>(
      "/r1/body/finger/twist", 10, [&](const geometry_msgs::TwistStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        twist = *m;
      });
  mb_kinematics_msgs::LowerBodyArray topology;
  ros::Subscriber topology_sub = nh.subscribe<mb_kinematics_msgs::LowerBodyArray>(
      "/r2/lower_body_array", 1, [&](const mb_kinematics_msgs::LowerBodyArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        topology = *m;
      });
  const mbk::Model model = test_model();
  std::vector<ros::Publisher> states;
  std::vector<std::unique_ptr<KinematicsRecorder>> recorders;
  for (const std::string ns : {"/r1", "/r2"}) {
    states.push_back(nh.advertise<sensor_msgs::JointState>(ns + "/joint_states", 100));
    recorders.push_back(std::make_unique<KinematicsRecorder>(nh, ns + "/body_kinematics"));
    connect(states.back(), *recorders.back());
  }
  ASSERT_TRUE(wait_until([&] { return twist_sub.getNumPublishers() > 0; }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Quadratic trajectory(model, 0.2);
  const ros::Time start(100.0);
  for (int i = 0; i < 4; ++i) {
    for (auto& p : states)
      p.publish(
          joint_state_msg(model, trajectory.at(i * kDt), start + ros::Duration(i * kDt), false));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const ros::Time last = start + ros::Duration(3 * kDt);
  for (auto& r : recorders) ASSERT_TRUE(r->wait_for(last));
  ASSERT_TRUE(
      wait_until([&] { return buffer.canTransform("r2/base_link", "r2/finger", last); }, 5));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::lock_guard<std::mutex> lock(mutex);
  int r1 = 0, r2 = 0;
  for (const std::string& f : frames) {
    EXPECT_TRUE(starts_with(f, "r1/") || starts_with(f, "r2/")) << "unprefixed frame " << f;
    r1 += starts_with(f, "r1/");
    r2 += starts_with(f, "r2/");
  }
  EXPECT_EQ(r1, model.body_count() + 1) << "R and every body";
  EXPECT_EQ(r2, model.body_count() + 1);
  const mbk::Data<double> d = expected_kinematics(model, trajectory.at(3 * kDt));
  const int finger = model.body_index("finger");
  for (const std::string prefix : {"r1/", "r2/"}) {
    const auto t = buffer.lookupTransform(prefix + "base_link", prefix + "finger", last);
    expect_near(vec(t.transform.translation), d.origin[finger], kTol, prefix + "finger");
  }
  for (size_t i = 0; i < recorders.size(); ++i) {
    const auto msgs = recorders[i]->at(last);
    ASSERT_EQ(msgs.size(), 1u);
    EXPECT_EQ(msgs[0].header.frame_id, i == 0 ? "r1/base_link" : "r2/base_link");
    EXPECT_EQ(msgs[0].bodies[finger - 1].name, "finger");  // the model's name
  }
  EXPECT_EQ(twist.header.frame_id, "r1/finger");
  EXPECT_EQ(topology.header.frame_id, "r2/base_link");
  EXPECT_EQ(topology.names[finger - 1], "finger");
}

// ~per_body_topics as a list (r2: [finger, arm1]): topics for those bodies only; true (r1):
// for every body.
TEST(PerBodyTopicsTest, ListNamesTheBodies) {
  auto advertised = [](const std::string& topic) {
    ros::master::V_TopicInfo topics;
    ros::master::getTopics(topics);
    for (const auto& t : topics)
      if (t.name == topic) return true;
    return false;
  };
  ASSERT_TRUE(wait_until([&] { return advertised("/r2/body/finger/twist"); }, 10));
  for (const char* body : {"finger", "arm1"})
    for (const char* kind : {"twist", "accel"})
      EXPECT_TRUE(advertised(std::string("/r2/body/") + body + "/" + kind)) << body << kind;
  for (const char* body : {"slider", "floater", "camera", "arm2", "tool"}) {
    EXPECT_FALSE(advertised(std::string("/r2/body/") + body + "/twist")) << body;
    EXPECT_TRUE(advertised(std::string("/r1/body/") + body + "/twist")) << body;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "frame_prefix_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
