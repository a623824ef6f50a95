// mb_kinematics_node with ~publish_markers (markers.test): body_kinematics/markers carries, for a
// moving robot, arrows of each quantity at the mass centers, a sphere per body, all finite; and
// only while someone listens (then body_kinematics itself need not have subscribers).
#include <visualization_msgs/MarkerArray.h>

#include <atomic>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

TEST(MarkersTest, ArrowsPerBodyWithFinitePoints) {
  ros::NodeHandle nh;
  const mbk::Model model = test_model();
  std::mutex mutex;
  visualization_msgs::MarkerArray last;
  std::atomic<int> received{0};
  ros::Subscriber sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "body_kinematics/markers", 10, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        last = *m;
        ++received;
      });
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  ASSERT_TRUE(
      wait_until([&] { return sub.getNumPublishers() > 0 && states.getNumSubscribers() > 0; }, 10));
  const Quadratic trajectory(model, 1.5);
  for (int i = 0; i < 6; ++i) {
    states.publish(
        joint_state_msg(model, trajectory.at(i * 0.02), ros::Time(100.0 + i * 0.02), true));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(wait_until([&] { return received >= 3; }, 10)) << "no body_kinematics/markers";
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_FALSE(last.markers.empty());
  EXPECT_EQ(last.markers[0].action, visualization_msgs::Marker::DELETEALL);
  std::map<std::string, int> arrows;
  std::vector<mbk::Vec3<double>> mass_centers;
  for (const auto& m : last.markers) {
    if (m.action == visualization_msgs::Marker::DELETEALL) continue;
    EXPECT_EQ(m.header.frame_id, "base_link");
    for (const auto& p : m.points) EXPECT_TRUE(vec(p).allFinite()) << m.ns << " " << m.id;
    EXPECT_TRUE(std::isfinite(m.scale.x) && m.scale.x > 0) << m.ns;
    if (m.type == visualization_msgs::Marker::ARROW) ++arrows[m.ns];
    if (m.ns == "mass_centers")
      for (const auto& p : m.points) mass_centers.push_back(vec(p));
  }
  EXPECT_EQ(mass_centers.size(), static_cast<size_t>(model.body_count()));
  // Every body but the fixed camera moves, and all but the slider (prismatic on R) turn.
  const int n = model.body_count();
  EXPECT_EQ(arrows["velocity"], n - 1);
  EXPECT_EQ(arrows["acceleration"], n - 1);
  EXPECT_EQ(arrows["omega"], n - 2);
  EXPECT_EQ(arrows["alpha"], n - 2);
  for (const auto& m : last.markers) {
    if (m.ns != "velocity") continue;
    const mbk::Vec3<double> start = vec(m.pose.position) + vec(m.points[0]);
    const bool at_mass_center =
        std::any_of(mass_centers.begin(), mass_centers.end(),
                    [&](const auto& g) { return (g - start).norm() < 1e-9; });
    EXPECT_TRUE(at_mass_center) << "velocity arrow " << m.id << " not at a mass center";
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "markers_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
