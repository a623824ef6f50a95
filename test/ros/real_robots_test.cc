// The real-robot conformance set (issue 25): for the published robot description on
// /robot_description (real_robots.test), the node's /tf and /tf_static agree with
// robot_state_publisher's on the same joint_states stream to 1e-12 m and 1e-12 rad (the angle of
// the quaternion difference), mimic joints published off their rule included (the published
// value wins, as in robot_state_publisher), and body_kinematics' system mass is the URDF's sum.
#include <tf2_msgs/TFMessage.h>

#include <map>

#include "mb_kinematics/io/urdf_model.h"
#include "test/ros/ros_test_support.h"
#include "test/support/urdf_facts.h"

using namespace mbk_ros_test;

namespace {

using Key = std::pair<std::string, double>;  // child frame, stamp (0 for /tf_static)

class Transforms {
 public:
  Transforms(ros::NodeHandle& nh, const std::string& topic, bool latched)
      : latched_(latched), sub_(nh.subscribe(topic, 1000, &Transforms::on, this)) {}
  bool connected() const { return sub_.getNumPublishers() > 0; }
  std::map<Key, geometry_msgs::TransformStamped> get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return transforms_;
  }

 private:
  void on(const tf2_msgs::TFMessage& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& t : msg.transforms)
      transforms_[{t.child_frame_id, latched_ ? 0.0 : t.header.stamp.toSec()}] = t;
  }
  bool latched_;
  mutable std::mutex mutex_;
  std::map<Key, geometry_msgs::TransformStamped> transforms_;
  ros::Subscriber sub_;
};

// Largest translation (m) and rotation (rad, 2 asin |vec(q_a^-1 q_b)|) differences.
void compare(const std::map<Key, geometry_msgs::TransformStamped>& ours,
             const std::map<Key, geometry_msgs::TransformStamped>& theirs, double& position,
             double& rotation) {
  for (const auto& [key, t] : theirs) {
    const auto it = ours.find(key);
    ASSERT_NE(it, ours.end()) << "no tf of ours for " << key.first << " at " << key.second;
    EXPECT_EQ(it->second.header.frame_id, t.header.frame_id) << key.first;
    position = std::max(
        position, (vec(it->second.transform.translation) - vec(t.transform.translation)).norm());
    const auto& a = it->second.transform.rotation;
    const auto& b = t.transform.rotation;
    const Eigen::Quaterniond qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
    const Eigen::Quaterniond d = qa.conjugate() * qb;
    rotation = std::max(rotation, 2 * std::asin(std::min(1.0, d.vec().norm())));
  }
}

TEST(RealRobots, NodeAgreesWithRobotStatePublisher) {
  ros::NodeHandle nh;
  std::string xml;
  ASSERT_TRUE(nh.getParam("/robot_description", xml));
  const mbk::Model model = mbk::load_urdf_string(xml);
  Transforms ours(nh, "/tf", false), theirs(nh, "/rsp_tf", false),
      ours_static(nh, "/tf_static", true), theirs_static(nh, "/rsp_tf_static", true);
  KinematicsRecorder kinematics(nh, "body_kinematics");
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  ASSERT_TRUE(wait_until(
      [&] {
        return states.getNumSubscribers() >= 2 && ours.connected() && theirs.connected() &&
               kinematics.connected();
      },
      20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Quadratic trajectory(model);
  const int samples = 10;              // 10 ms apart: the node estimates the accelerations
  for (int i = 0; i < samples; ++i) {  // every coordinate, the mimics 0.01 off their rule:
    mbk::JointState<double> state = trajectory.at(i * 0.01);  // a published value wins in both
    for (const mbk::Mimic& m : model.mimics) state.position[m.coordinate] += 0.01;
    states.publish(
        joint_state_msg(model, state, ros::Time(50.0 + i * 0.01), true, model.coordinate_names));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(wait_until([&] { return kinematics.count() > 0; }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  double position = 0, rotation = 0;
  const auto mine = ours.get(), rsp = theirs.get();
  EXPECT_FALSE(rsp.empty() && ours_static.get().empty());
  compare(mine, rsp, position, rotation);
  compare(ours_static.get(), theirs_static.get(), position, rotation);
  std::printf("  %zu moving and %zu fixed transforms: %.1e m, %.1e rad\n", rsp.size(),
              theirs_static.get().size(), position, rotation);
  EXPECT_LT(position, 1e-12);
  EXPECT_LT(rotation, 1e-12);
  const double sum = mbk_test::urdf_mass_sum(xml);
  EXPECT_NEAR(kinematics.latest().system.mass, sum, 1e-12 * sum);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "real_robots_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
