// Every transform robot_state_publisher publishes for test_robot.urdf must equal ours, for the
// same joint states (rsp_compare.test). robot_state_publisher (KDL) has no floating joint: it
// publishes nothing for `floater`, which NodeTest.TfMatchesClosedForms covers.
#include <tf2_msgs/TFMessage.h>

#include <map>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

using Key = std::pair<std::string, double>;  // child frame, stamp

class TfRecorder {
 public:
  TfRecorder(ros::NodeHandle& nh, const std::string& topic)
      : sub_(nh.subscribe(topic, 100, &TfRecorder::on_message, this)) {}
  bool connected() const { return sub_.getNumPublishers() > 0; }
  std::map<Key, geometry_msgs::TransformStamped> get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return transforms_;
  }

 private:
  void on_message(const tf2_msgs::TFMessage& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& t : msg.transforms)
      transforms_[{t.child_frame_id, t.header.stamp.toSec()}] = t;
  }
  mutable std::mutex mutex_;
  std::map<Key, geometry_msgs::TransformStamped> transforms_;
  ros::Subscriber sub_;
};

void expect_same(const geometry_msgs::TransformStamped& ours,
                 const geometry_msgs::TransformStamped& theirs) {
  const std::string what =
      theirs.child_frame_id + " at " + std::to_string(theirs.header.stamp.toSec());
  EXPECT_EQ(ours.header.frame_id, theirs.header.frame_id) << what;
  expect_near(vec(ours.transform.translation), vec(theirs.transform.translation), 1e-9,
              what + " translation");
  const auto& a = ours.transform.rotation;
  const auto& b = theirs.transform.rotation;
  const Eigen::Quaterniond qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
  EXPECT_LT(qa.angularDistance(qb), 1e-9) << what << " rotation";
}

TEST(RspCompareTest, SameTransformsAsRobotStatePublisher) {
  ros::NodeHandle nh;
  const mbk::Model model = test_model();
  TfRecorder ours(nh, "/tf"), theirs(nh, "/rsp_tf"), ours_static(nh, "/tf_static"),
      theirs_static(nh, "/rsp_tf_static");
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  ASSERT_TRUE(wait_until(
      [&] {
        return states.getNumSubscribers() >= 2 && ours.connected() && theirs.connected() &&
               ours_static.connected() && theirs_static.connected();
      },
      10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Quadratic trajectory(model);
  const int samples = 5;
  for (int i = 0; i < samples; ++i) {
    // robot_state_publisher wants the mimic's source only; it publishes what it can compute.
    states.publish(joint_state_msg(model, trajectory.at(i * 0.3), ros::Time(50.0 + i), false));
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  ASSERT_TRUE(wait_until([&] { return theirs.get().size() >= samples * 4u; }, 5))
      << "robot_state_publisher published " << theirs.get().size() << " transforms";
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto mine = ours.get();
  int compared = 0;
  for (const auto& [key, t] : theirs.get()) {
    auto it = mine.find(key);
    ASSERT_NE(it, mine.end()) << "no tf of ours for " << key.first << " at " << key.second;
    expect_same(it->second, t);
    ++compared;
  }
  EXPECT_EQ(compared, samples * 4);  // slider, arm1, arm2, finger (mimic) per sample
  int compared_static = 0;
  ASSERT_TRUE(wait_until([&] { return theirs_static.get().size() >= 2u; }, 5));
  for (const auto& [key, t] : theirs_static.get()) {
    bool found = false;
    for (const auto& [our_key, our_t] : ours_static.get())
      if (our_key.first == key.first) {
        expect_same(our_t, t);
        found = true;
      }
    EXPECT_TRUE(found) << "no static tf of ours for " << key.first;
    ++compared_static;
  }
  EXPECT_EQ(compared_static, 2);  // camera, tool
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "rsp_compare_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
