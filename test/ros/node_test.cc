// mb_kinematics_node against values computed here independently: closed forms of the test
// robot's joints for /tf, the partial-velocity formulation for body_kinematics (node.test).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <mb_kinematics_msgs/LowerBodyArray.h>
#include <sys/wait.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/transform_listener.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <numeric>
#include <set>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;
using Eigen::AngleAxisd;
using mbk::Vec3;

namespace {

constexpr double kTol = 1e-6;
const double kDt = 0.02;  // 50 Hz

class NodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 100);
    connect(states_, recorder_);
  }
  void publish(const mbk::JointState<double>& s, const ros::Time& stamp, bool velocities,
               const std::vector<std::string>& names = {}) {
    states_.publish(joint_state_msg(model_, s, stamp, velocities, names));
  }
  // Publishes samples i = 0..n-1 at start + i dt of `trajectory` and waits for the last one's
  // body_kinematics (if `wait`).
  void publish_run(const Quadratic& trajectory, const ros::Time& start, int n, bool velocities) {
    for (int i = 0; i < n; ++i) {
      publish(trajectory.at(i * kDt), start + ros::Duration(i * kDt), velocities);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  }

  ros::NodeHandle nh_;
  mbk::Model model_ = test_model();
  ros::Publisher states_;
  KinematicsRecorder recorder_{nh_, "body_kinematics"};
};

TEST_F(NodeTest, LatchedTopology) {
  mb_kinematics_msgs::LowerBodyArray topology;
  ASSERT_TRUE(latched_lower_body_array(nh_, topology));
  EXPECT_EQ(topology.header.frame_id, "base_link");
  const std::vector<std::string> names = {"slider", "floater", "camera", "arm1",
                                          "arm2",   "tool",    "finger"};
  EXPECT_EQ(topology.names, names);
  EXPECT_EQ(topology.lower, std::vector<uint32_t>({0, 0, 0, 1, 4, 5, 6}));
}

void expect_transform(const tf2_ros::Buffer& buffer, const std::string& parent,
                      const std::string& child, const ros::Time& stamp, const Vec3<double>& p,
                      const Eigen::Matrix3d& r) {
  const geometry_msgs::TransformStamped t = buffer.lookupTransform(parent, child, stamp);
  EXPECT_EQ(t.header.stamp, stamp) << child;
  expect_near(vec(t.transform.translation), p, kTol, parent + " -> " + child + " translation");
  const auto& q = t.transform.rotation;
  EXPECT_LT((Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix() - r).norm(), kTol)
      << parent << " -> " << child << " rotation";
}

Eigen::Matrix3d rot(double angle, const Vec3<double>& axis) {
  return AngleAxisd(angle, axis).toRotationMatrix();
}

// Closed forms of test_robot.urdf's joints; fixed joints come from /tf_static.
TEST_F(NodeTest, TfMatchesClosedForms) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Quadratic trajectory(model_);
  const mbk::JointState<double> s = trajectory.at(0.7);
  const ros::Time stamp(100.0);
  publish(s, stamp, false);
  ASSERT_TRUE(wait_until([&] { return buffer.canTransform("base_link", "finger", stamp); }, 5));
  auto q = [&](const std::string& name) { return s.position[model_.coordinate_index(name)]; };
  const Vec3<double> x = Vec3<double>::UnitX(), y = Vec3<double>::UnitY(),
                     z = Vec3<double>::UnitZ();
  expect_transform(buffer, "base_link", "slider", stamp, Vec3<double>(q("slider_joint"), 0, 0.1),
                   Eigen::Matrix3d::Identity());
  expect_transform(buffer, "slider", "arm1", stamp, Vec3<double>(0, 0, 0.2),
                   rot(0.3 + q("arm1_joint"), z));
  expect_transform(buffer, "arm1", "arm2", stamp, Vec3<double>(0.5, 0, 0), rot(q("arm2_joint"), y));
  expect_transform(buffer, "tool", "finger", stamp, Vec3<double>(0, 0, 0.1),
                   rot(2 * q("arm2_joint") + 0.1, x));  // the mimic
  expect_transform(buffer, "base_link", "floater", stamp,
                   Vec3<double>(1 + q("float_joint/x"), q("float_joint/y"), q("float_joint/z")),
                   rot(q("float_joint/alpha"), x) * rot(q("float_joint/beta"), y) *
                       rot(q("float_joint/gamma"), z));  // 1-2-3 angles
  expect_transform(buffer, "arm2", "tool", stamp, Vec3<double>(0.3, 0, 0), rot(0.1, x));
  expect_transform(buffer, "base_link", "camera", ros::Time(0), Vec3<double>(0, 0.5, 1),
                   rot(0.5, y));
  // The composed chain against the partial-velocity formulation's absolute pose.
  const mbk::Data<double> d = expected_kinematics(model_, s);
  const int finger = model_.body_index("finger");
  expect_transform(buffer, "base_link", "finger", stamp, d.origin[finger], d.rotation[finger]);
}

// Without velocities: both derivatives from positions; exact for a quadratic once three samples
// are in; nothing published before (no velocity/acceleration estimates yet).
TEST_F(NodeTest, KinematicsFromPositionsOnly) {
  const Quadratic trajectory(model_, 1.0);
  const ros::Time start(200.0);
  publish_run(trajectory, start, 4, false);
  EXPECT_TRUE(recorder_.at(start).empty());
  EXPECT_TRUE(recorder_.at(start + ros::Duration(kDt)).empty());
  for (int i = 2; i < 4; ++i) {
    const auto msgs = recorder_.at(start + ros::Duration(i * kDt));
    ASSERT_EQ(msgs.size(), 1u) << "sample " << i;
    expect_kinematics(msgs[0], model_, expected_kinematics(model_, trajectory.at(i * kDt)), kTol);
  }
}

// /diagnostics carries the cheap error indicators; on a quadratic trajectory the prediction
// residual of the 3-point difference (exact for quadratics) is rounding only.
TEST_F(NodeTest, DiagnosticsReportErrorIndicators) {
  std::vector<std::pair<ros::WallTime, std::map<std::string, std::string>>> received;
  std::mutex mutex;
  ros::Subscriber sub = nh_.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& status : m->status) {
          if (status.name.find("Joint state input") == std::string::npos) continue;
          std::map<std::string, std::string> values;
          for (const auto& kv : status.values) values[kv.key] = kv.value;
          if (values.count("samples received") == 0) continue;
          std::lock_guard<std::mutex> lock(mutex);
          received.push_back({ros::WallTime::now(), values});
        }
      });
  const Quadratic trajectory(model_, 0.5);
  const ros::Time start(400.0);
  const ros::WallTime run_start = ros::WallTime::now();
  publish_run(trajectory, start, 400, false);  // >= 4 s at 10 ms per sample
  const ros::WallTime run_end = ros::WallTime::now();
  std::lock_guard<std::mutex> lock(mutex);
  int checked = 0;
  for (const auto& [when, values] : received) {
    // Windows that lie wholly inside the run (diagnostics every 1 s; margin 0.2 s).
    if (when < run_start + ros::WallDuration(1.2) || when > run_end) continue;
    ++checked;
    EXPECT_EQ(values.at("acceleration estimator"), "backward_difference");
    EXPECT_LT(std::stod(values.at("estimator residual, max (rad or m)")), 1e-9);
    EXPECT_LT(std::stod(values.at("rotation orthonormality drift")), 1e-12);
    EXPECT_EQ(std::stod(values.at("Euler parameter norm error")), 0.0);  // no Euler joints
  }
  EXPECT_GT(checked, 0) << received.size() << " diagnostics received in all";
}

// With velocities: accelerations from the given velocities, from the second sample on.
TEST_F(NodeTest, KinematicsWithGivenVelocities) {
  const Quadratic trajectory(model_, 2.0);
  const ros::Time start(300.0);
  publish_run(trajectory, start, 3, true);
  EXPECT_TRUE(recorder_.at(start).empty());
  for (int i = 1; i < 3; ++i) {
    const auto msgs = recorder_.at(start + ros::Duration(i * kDt));
    ASSERT_EQ(msgs.size(), 1u) << "sample " << i;
    expect_kinematics(msgs[0], model_, expected_kinematics(model_, trajectory.at(i * kDt)), kTol);
  }
}

// Bad messages: dropped whole; the node stays up and goes on with the next good sample.
TEST_F(NodeTest, BadInputPublishesNothing) {
  std::set<double> tf_stamps;
  std::mutex mutex;
  ros::Subscriber tf_sub =
      nh_.subscribe<tf2_msgs::TFMessage>("/tf", 100, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& t : m->transforms) tf_stamps.insert(t.header.stamp.toSec());
      });
  ASSERT_TRUE(wait_until([&] { return tf_sub.getNumPublishers() > 0; }, 5));
  const Quadratic trajectory(model_, 3.0);
  const ros::Time start(400.0);
  publish_run(trajectory, start, 3, true);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<sensor_msgs::JointState> bad;
  auto good = [&](int i) {
    return joint_state_msg(model_, trajectory.at(i * kDt), start + ros::Duration(i * kDt), true);
  };
  bad.push_back(good(3)), bad.back().position.pop_back();           // unequal lengths
  bad.push_back(good(4)), bad.back().velocity.resize(2);            // unequal lengths
  bad.push_back(good(5)), bad.back().name[1] = bad.back().name[0];  // duplicate name
  bad.push_back(good(6)), bad.back().position[2] = nan;             // NaN
  bad.push_back(good(7)), bad.back().velocity[0] = inf;             // Inf
  bad.push_back(good(8)), bad.back().name = {"elbow"};              // only unknown names
  bad.back().position = {0.1};
  bad.back().velocity = {0.1};
  bad.push_back(good(9)), bad.back().position[0] = 1e60;  // beyond mbk::kMaxStateMagnitude
  for (const auto& m : bad) states_.publish(m);
  // A good sample with an unknown name as well: accepted, the unknown name ignored.
  sensor_msgs::JointState extra = good(10);
  extra.name.push_back("not_in_the_model");
  extra.position.push_back(nan);  // its value does not matter
  extra.velocity.push_back(0);
  states_.publish(extra);
  ASSERT_TRUE(recorder_.wait_for(extra.header.stamp)) << "the node died or stopped publishing";
  for (const auto& m : bad) {
    EXPECT_TRUE(recorder_.at(m.header.stamp).empty()) << "published at " << m.header.stamp;
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_EQ(tf_stamps.count(m.header.stamp.toSec()), 0u) << "tf at " << m.header.stamp;
  }
  // Accelerations are estimated from the velocities of the accepted samples (0, 1, 2 and 10).
  const auto msgs = recorder_.at(extra.header.stamp);
  ASSERT_EQ(msgs.size(), 1u);
  expect_kinematics(msgs[0], model_, expected_kinematics(model_, trajectory.at(10 * kDt)), kTol);
}

// A bag looping: stamps jump back; the estimates restart instead of differencing across the
// jump (no body_kinematics until three new samples), then are exact again.
TEST_F(NodeTest, BackwardsJumpRestartsEstimates) {
  const Quadratic before(model_, 4.0), after(model_, 5.0);
  publish_run(before, ros::Time(600.0), 3, false);
  const ros::Time start(500.0);
  publish_run(after, start, 4, false);
  EXPECT_TRUE(recorder_.at(start).empty());
  EXPECT_TRUE(recorder_.at(start + ros::Duration(kDt)).empty());
  for (int i = 2; i < 4; ++i) {
    const auto msgs = recorder_.at(start + ros::Duration(i * kDt));
    ASSERT_EQ(msgs.size(), 1u);
    expect_kinematics(msgs[0], model_, expected_kinematics(model_, after.at(i * kDt)), kTol);
  }
}

// Two publishers with disjoint joints (the /fresh node has seen no joint before): nothing is
// published while joints are missing; merged samples are exact.
TEST(FreshNodeTest, MergesTwoPublishersAndWaitsForMissingJoints) {
  ros::NodeHandle nh("fresh");
  const mbk::Model model = test_model();
  ros::Publisher arm = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  ros::Publisher base = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  KinematicsRecorder recorder(nh, "body_kinematics");
  connect(arm, recorder);
  const std::vector<std::string> arm_joints = {"arm1_joint", "arm2_joint"};
  const std::vector<std::string> base_joints = {
      "slider_joint",      "float_joint/x",    "float_joint/y",    "float_joint/z",
      "float_joint/alpha", "float_joint/beta", "float_joint/gamma"};
  const Quadratic trajectory(model, 6.0);
  const ros::Time start(700.0);
  auto stamp = [&](int i) { return start + ros::Duration(i * kDt); };
  for (int i = 0; i < 3; ++i)
    arm.publish(joint_state_msg(model, trajectory.at(i * kDt), stamp(i), false, arm_joints));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(recorder.count(), 0u) << "published with joints missing";
  for (int i = 0; i < 3; ++i)
    base.publish(joint_state_msg(model, trajectory.at(i * kDt), stamp(i), false, base_joints));
  ASSERT_TRUE(recorder.wait_for(stamp(2)));
  EXPECT_TRUE(recorder.at(stamp(0)).empty());
  EXPECT_TRUE(recorder.at(stamp(1)).empty());
  const auto msgs = recorder.at(stamp(2));
  ASSERT_EQ(msgs.size(), 1u);
  expect_kinematics(msgs[0], model, expected_kinematics(model, trajectory.at(2 * kDt)), kTol);
}

// ~publish_frequency 10 on a 50 Hz positions-only stream: outputs for one sample in five (by
// stamp), while the estimators take in every sample: the first output with accelerations, at
// sample 5, needs the three samples 3, 4, 5 (the published ones alone, 0 and 5, are too few).
TEST(DecimatedNodeTest, PublishFrequencyDecimatesOutputsNotEstimates) {
  ros::NodeHandle nh("decimated");
  const mbk::Model model = test_model();
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  KinematicsRecorder recorder(nh, "body_kinematics");
  connect(states, recorder);
  const Quadratic trajectory(model, 7.0);
  const ros::Time start(800.0);
  auto stamp = [&](int i) { return start + ros::Duration(i * kDt); };
  const int n = 21;
  for (int i = 0; i < n; ++i) {
    states.publish(joint_state_msg(model, trajectory.at(i * kDt), stamp(i), false));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(recorder.wait_for(stamp(n - 1)));
  for (int i = 0; i < n; ++i) {
    const auto msgs = recorder.at(stamp(i));
    if (i % 5 != 0 || i == 0) {
      EXPECT_TRUE(msgs.empty()) << "published at sample " << i;
      continue;
    }
    ASSERT_EQ(msgs.size(), 1u) << "sample " << i;
    expect_kinematics(msgs[0], model, expected_kinematics(model, trajectory.at(i * kDt)), kTol);
  }
  EXPECT_EQ(recorder.count(), 4u);
}

// A robot_description that does not parse: a clear error and a non-zero exit.
TEST(StartupTest, BadRobotDescriptionExitsNonZero) {
  ros::NodeHandle nh;
  nh.setParam("/broken/robot_description", "<robot name='x'><link name='a'/><joint");
  std::string output;
  EXPECT_GT(run_node("__ns:=/broken __name:=broken_node", output), 0);
  EXPECT_NE(output.find("robot_description"), std::string::npos) << output;
  EXPECT_NE(output.find("does not parse"), std::string::npos) << output;
}

// A centered estimator lags the newest sample; the node pairs estimates with it, so it must
// refuse such an estimator at start instead of publishing misaligned accelerations.
TEST(StartupTest, EstimatorWithLatencyExitsNonZero) {
  ros::NodeHandle nh;
  std::string urdf;
  ASSERT_TRUE(nh.getParam("/robot_description", urdf));
  nh.setParam("/lagging/robot_description", urdf);
  std::string output;
  EXPECT_GT(run_node("__ns:=/lagging __name:=lagging_node"
                     " _acceleration_estimator:=savitzky_golay_9_2",
                     output),
            0);
  EXPECT_NE(output.find("savitzky_golay_9_2"), std::string::npos) << output;
  EXPECT_NE(output.find("4 samples back"), std::string::npos) << output;
}

TEST(StartupTest, BadQueueSizeExitsNonZero) {
  ros::NodeHandle nh;
  std::string urdf;
  ASSERT_TRUE(nh.getParam("/robot_description", urdf));
  nh.setParam("/queue/robot_description", urdf);
  std::string output;
  EXPECT_GT(run_node("__ns:=/queue __name:=queue_node _queue_size:=0", output), 0);
  EXPECT_NE(output.find("queue_size must be >= 1"), std::string::npos) << output;
}

// The start-up log is one INFO line (bodies, coordinates, depth, what is computed); the lower
// body arrays table is at DEBUG: a chain of 60 bodies (3660 cells) starts in one short line.
TEST(StartupTest, StartupLogIsOneInfoLineTheTableAtDebug) {
  std::vector<int> chain(60);
  std::iota(chain.begin(), chain.end(), 0);  // L(k) = k - 1
  ros::NodeHandle nh;
  nh.setParam("/chain/chain_node/lower_body_array", chain);
  const std::string command =
      "timeout -s INT 5 " + std::string(MBK_NODE_PATH) + " __ns:=/chain __name:=chain_node 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 124) << "the node ended before the timeout:\n" << output;
  const size_t line = output.find("60 bodies, 180 coordinates, max depth 60");
  ASSERT_NE(line, std::string::npos) << output;
  EXPECT_NE(output.find("momentum left out", line), std::string::npos) << output;
  EXPECT_EQ(output.find("Lower body arrays"), std::string::npos) << "the table at INFO:\n"
                                                                 << output;
  EXPECT_LT(output.size(), 600u) << output;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
