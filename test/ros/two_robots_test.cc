// launch/two_robots.launch (two_robots.test): two nodes on the human body URDF, ~frame_prefix
// robot1/ and robot2/, each moved by its own demo_publisher. No frame collides: every child
// frame on /tf and /tf_static has one parent from one node; each node's frames carry its prefix
// and cover every body; body names in body_kinematics stay the model's, in each robot's R; one
// tf tree holds both (world -> robotN/world -> every body).
#include <tf2_ros/transform_listener.h>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

TEST(TwoRobots, NoFrameCollides) {
  ros::NodeHandle nh;
  const mbk::Model model = mbk::load_urdf_file(source_path("config/human_body.urdf"));
  TfRecorder tf(nh);
  KinematicsRecorder robot1(nh, "/robot1/body_kinematics"), robot2(nh, "/robot2/body_kinematics");
  ASSERT_TRUE(wait_until([&] { return robot1.count() > 20 && robot2.count() > 20; }, 30))
      << "both robots publish body_kinematics";
  std::this_thread::sleep_for(std::chrono::seconds(1));
  for (const auto& [child, sources] : tf.by_child())
    EXPECT_EQ(sources.size(), 1u) << child << " has more than one parent or publisher";
  const auto by_publisher = tf.by_publisher();
  for (const std::string robot : {"robot1", "robot2"}) {
    SCOPED_TRACE(robot);
    const auto it = by_publisher.find("/" + robot + "/mb_kinematics");
    ASSERT_NE(it, by_publisher.end()) << "no transform from the node";
    EXPECT_EQ(it->second.size(), static_cast<size_t>(model.body_count())) << "a frame per body";
    for (const std::string& t : it->second) {
      const size_t arrow = t.find(" -> ");
      EXPECT_TRUE(starts_with(t.substr(0, arrow), robot + "/")) << t;
      EXPECT_TRUE(starts_with(t.substr(arrow + 4), robot + "/")) << t;
    }
  }
  for (const KinematicsRecorder* r : {&robot1, &robot2}) {
    ASSERT_GT(r->count(), 0u);
    const auto last = r->latest();
    EXPECT_EQ(last.header.frame_id, r == &robot1 ? "robot1/world" : "robot2/world");
    ASSERT_EQ(last.bodies.size(), static_cast<size_t>(model.body_count()));
    for (int k = 1; k <= model.body_count(); ++k)
      EXPECT_EQ(last.bodies[k - 1].name, model.bodies[k].name);
  }
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  for (const std::string robot : {"robot1", "robot2"})
    EXPECT_TRUE(buffer.canTransform("world", robot + "/left_foot", ros::Time(0), ros::Duration(5)))
        << robot << "/left_foot is not in the tree under world";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "two_robots_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
