// Two mb_kinematics_node under hostile streams (hostile.test): random mixes of valid partial
// samples; arrays of unequal length, unknown names, NaN/Inf, huge values; stamps zero,
// backwards, far in the future; empty messages and 10 kHz bursts; two publishers with disjoint
// joints; joint_accelerations with mismatched stamps. After each case: both nodes are up, no
// output carried a non-finite number, and one second of valid positions-only samples brings
// back correct body_kinematics (the core's partial-velocity formulation on the same state;
// for the kalman_smooth node, whose estimates are not exact, poses exactly and velocities and
// accelerations within the motion's own scale).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/AccelStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <mb_kinematics_msgs/JointAccelerations.h>
#include <ros/master.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <random>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;
constexpr double kDt = 0.02;  // valid samples at 50 Hz
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

bool finite(const geometry_msgs::Vector3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const geometry_msgs::Point& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const geometry_msgs::Quaternion& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

// Counts every message and every non-finite number on the nodes' outputs.
class FiniteWatch {
 public:
  explicit FiniteWatch(ros::NodeHandle& nh) {
    subs_.push_back(nh.subscribe<tf2_msgs::TFMessage>(
        "/tf", 1000, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
          for (const auto& t : m->transforms)
            note(finite(t.transform.translation) && finite(t.transform.rotation));
        }));
    for (const std::string topic : {"/body_kinematics", "/kalman/body_kinematics"})
      subs_.push_back(nh.subscribe<mb_kinematics_msgs::BodyKinematicsArray>(
          topic, 1000, [this](const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& m) {
            for (const auto& b : m->bodies)
              note(finite(b.pose.position) && finite(b.pose.orientation) && finite(b.mass_center) &&
                   finite(b.twist.angular) && finite(b.twist.linear) && finite(b.accel.angular) &&
                   finite(b.accel.linear));
          }));
    subs_.push_back(nh.subscribe<geometry_msgs::TwistStamped>(
        "/kalman/body/tool/twist", 1000, [this](const geometry_msgs::TwistStamped::ConstPtr& m) {
          note(finite(m->twist.angular) && finite(m->twist.linear));
        }));
    subs_.push_back(nh.subscribe<geometry_msgs::AccelStamped>(
        "/kalman/body/tool/accel", 1000, [this](const geometry_msgs::AccelStamped::ConstPtr& m) {
          note(finite(m->accel.angular) && finite(m->accel.linear));
        }));
    subs_.push_back(nh.subscribe<visualization_msgs::MarkerArray>(
        "/kalman/body_kinematics/markers", 100,
        [this](const visualization_msgs::MarkerArray::ConstPtr& m) {
          for (const auto& marker : m->markers) {
            bool ok = finite(marker.pose.position) && finite(marker.pose.orientation);
            for (const auto& p : marker.points) ok = ok && finite(p);
            note(ok);
          }
        }));
  }
  bool connected() const {
    for (const auto& s : subs_)
      if (s.getNumPublishers() == 0) return false;
    return true;
  }
  long bad() const { return bad_; }
  long seen() const { return seen_; }

 private:
  void note(bool ok) {
    ++seen_;
    if (!ok) ++bad_;
  }
  std::vector<ros::Subscriber> subs_;
  std::atomic<long> seen_{0}, bad_{0};
};

class HostileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const std::string ns : {"", "/kalman"})
      states_.push_back(nh_.advertise<sensor_msgs::JointState>(ns + "/joint_states", 5000));
    ASSERT_TRUE(wait_until(
        [&] {
          return states_[0].getNumSubscribers() > 0 && states_[1].getNumSubscribers() > 0 &&
                 exact_.connected() && kalman_.connected() && watch_.connected();
        },
        20))
        << "the nodes did not connect";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  void TearDown() override {
    EXPECT_GT(watch_.seen(), 0) << "the watch saw no output";
    EXPECT_EQ(watch_.bad(), 0) << "non-finite values published";
    EXPECT_TRUE(alive("/mb_kinematics") && alive("/kalman/mb_kinematics")) << "a node died";
  }
  static bool alive(const std::string& node) {
    std::vector<std::string> nodes;
    ros::master::getNodes(nodes);
    return std::find(nodes.begin(), nodes.end(), node) != nodes.end();
  }
  void send(const sensor_msgs::JointState& m) {
    for (auto& p : states_) p.publish(m);
  }
  // One second of valid positions-only samples of the case's own trajectory, right after its
  // last one (tau0; stamps base + tau, no pause that would restart the estimators anyway), at
  // 50 Hz; the last ten must come out correct from both nodes.
  void expect_recovery(const Quadratic& trajectory, const ros::Time& base, double tau0) {
    const int n = 50;
    for (int i = 0; i < n; ++i) {
      const double tau = tau0 + i * kDt;
      send(joint_state_msg(model_, trajectory.at(tau), base + ros::Duration(tau), false));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    for (int i = n - 10; i < n - 1; ++i) {  // the last may wait for its accelerations
      const double tau = tau0 + i * kDt;
      const ros::Time stamp = base + ros::Duration(tau);
      const mbk::JointState<double> s = trajectory.at(tau);
      const mbk::Data<double> d = expected_kinematics(model_, s);
      ASSERT_TRUE(exact_.wait_for(stamp)) << "no body_kinematics at recovery sample " << i;
      ASSERT_TRUE(kalman_.wait_for(stamp)) << "kalman: no body_kinematics at sample " << i;
      const auto exact = exact_.at(stamp), kalman = kalman_.at(stamp);
      expect_kinematics(exact.back(), model_, d, kTol);
      expect_motion_scale(kalman.back(), d);
    }
  }
  // Poses exact; velocities and accelerations within the motion's own scale: below 10 times
  // the largest of each over the bodies (and 1). kalman_smooth's estimates lag, so they are
  // not exact, but a poisoned estimator gives 1e95 or Inf here.
  void expect_motion_scale(const mb_kinematics_msgs::BodyKinematicsArray& msg,
                           const mbk::Data<double>& d) {
    double omega = 1, v = 1, alpha = 1, a = 1;
    for (int k = 1; k <= model_.body_count(); ++k) {
      omega = std::max(omega, d.omega[k].norm());
      v = std::max(v, d.mass_center_velocity[k].norm());
      alpha = std::max(alpha, d.alpha[k].norm());
      a = std::max(a, d.mass_center_acceleration[k].norm());
    }
    ASSERT_EQ(msg.bodies.size(), static_cast<size_t>(model_.body_count()));
    for (int k = 1; k <= model_.body_count(); ++k) {
      const auto& b = msg.bodies[k - 1];
      expect_near(vec(b.pose.position), d.origin[k], kTol, b.name + " origin");
      expect_near(vec(b.mass_center), d.mass_center[k], kTol, b.name + " mass center");
      EXPECT_LT(vec(b.twist.angular).norm(), 10 * omega) << b.name;
      EXPECT_LT(vec(b.twist.linear).norm(), 10 * v) << b.name;
      EXPECT_LT(vec(b.accel.angular).norm(), 10 * alpha) << b.name;
      EXPECT_LT(vec(b.accel.linear).norm(), 10 * a) << b.name;
    }
  }
  sensor_msgs::JointState valid(const Quadratic& trajectory, int i, const ros::Time& start,
                                bool velocities = false) {
    return joint_state_msg(model_, trajectory.at(i * kDt), start + ros::Duration(i * kDt),
                           velocities);
  }

  ros::NodeHandle nh_;
  mbk::Model model_ = test_model();
  std::vector<ros::Publisher> states_;
  KinematicsRecorder exact_{nh_, "/body_kinematics"}, kalman_{nh_, "/kalman/body_kinematics"};
  FiniteWatch watch_{nh_};
  std::mt19937 random_{14};
};

// Valid samples, mixed: random subsets of the coordinates, in random order, with and without
// velocities, from one trajectory.
TEST_F(HostileTest, RandomMixesOfValidSamples) {
  const Quadratic trajectory(model_, 0.3);
  const ros::Time start(1000.0);
  std::bernoulli_distribution coin(0.5);
  for (int i = 0; i < 300; ++i) {
    sensor_msgs::JointState full = valid(trajectory, i, start, coin(random_));
    sensor_msgs::JointState m;
    m.header = full.header;
    std::vector<size_t> order(full.name.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), random_);
    for (size_t j : order) {
      if (!coin(random_)) continue;
      m.name.push_back(full.name[j]);
      m.position.push_back(full.position[j]);
      if (!full.velocity.empty()) m.velocity.push_back(full.velocity[j]);
    }
    send(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  expect_recovery(trajectory, start, 300 * kDt);
}

// Each message a valid one with one defect.
TEST_F(HostileTest, MalformedAndHugeValues) {
  const Quadratic trajectory(model_, 0.5);
  const ros::Time start(2000.0);
  const double huge[] = {kNaN, kInf, -kInf, 1.7e308, 1e300, 1e60, 1e51, -1e200, 1e49};
  std::uniform_int_distribution<int> defect(0, 5), slot(0, 8), value(0, 8);
  for (int i = 0; i < 400; ++i) {
    sensor_msgs::JointState m = valid(trajectory, i, start, i % 2 == 0);
    switch (defect(random_)) {
      case 0:  // unequal lengths
        m.position.pop_back();
        break;
      case 1:
        m.velocity.resize(m.name.size() + 2, 0.0);
        break;
      case 2:  // unknown names, alone or beside known ones
        m.name[slot(random_)] = "no_such_joint";
        break;
      case 3:  // duplicate names
        m.name[1] = m.name[0];
        break;
      case 4:  // NaN, Inf, huge positions
        m.position[slot(random_)] = huge[value(random_)];
        break;
      default:  // and speeds
        if (m.velocity.empty()) m.velocity.assign(m.name.size(), 0.0);
        m.velocity[slot(random_)] = huge[value(random_)];
    }
    send(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  expect_recovery(trajectory, start, 400 * kDt);
}

// Single samples of 1.7e308, 1e300 on an angle (valid, but no motion) and
// 1e51, 1e300 on a translation (refused) in a positions-only stream. The estimators must not
// keep them: the stream goes on, and its own samples right after are correct again.
TEST_F(HostileTest, OneHugeSampleInAPositionsOnlyStream) {
  const Quadratic trajectory(model_, 0.6);
  const ros::Time start(2500.0);
  const std::map<int, std::pair<int, double>> spikes = {
      {25, {7, 1.7e308}}, {50, {7, 1e300}}, {75, {0, 1e51}}, {100, {0, 1e300}}};
  for (int i = 0; i < 125; ++i) {
    sensor_msgs::JointState m = valid(trajectory, i, start);  // slot 0 slider, 7 arm1
    if (spikes.count(i)) m.position[spikes.at(i).first] = spikes.at(i).second;
    send(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(4));
  }
  expect_recovery(trajectory, start, 125 * kDt);
}

// Stamps zero, backwards, far in the future, repeated.
TEST_F(HostileTest, BadStamps) {
  const Quadratic trajectory(model_, 0.7);
  const ros::Time start(3000.0);
  std::uniform_int_distribution<int> kind(0, 4);
  for (int i = 0; i < 300; ++i) {
    sensor_msgs::JointState m = valid(trajectory, i, start);
    switch (kind(random_)) {
      case 0:
        m.header.stamp = ros::Time(0);
        break;
      case 1:
        m.header.stamp = start - ros::Duration(100 + i);
        break;
      case 2:
        m.header.stamp = ros::Time(4e9);  // 2096
        break;
      case 3:
        m.header.stamp = start;
        break;
      default:
        break;
    }
    send(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  expect_recovery(trajectory, start, 300 * kDt);
}

// Empty messages, and 2,000 samples at 10 kHz (the nodes may drop some: their queues are
// bounded; they must not fall over).
TEST_F(HostileTest, EmptyMessagesAndBursts) {
  const Quadratic trajectory(model_, 0.9);
  const ros::Time start(4000.0);
  for (int i = 0; i < 50; ++i) {
    sensor_msgs::JointState empty;
    empty.header.stamp = start + ros::Duration(i * 1e-3);
    send(empty);
  }
  const auto begin = std::chrono::steady_clock::now();
  for (int i = 0; i < 2000; ++i) {
    sensor_msgs::JointState m = joint_state_msg(model_, trajectory.at(i * 1e-4),
                                                start + ros::Duration(1 + i * 1e-4), i % 3 == 0);
    send(m);
    std::this_thread::sleep_until(begin + std::chrono::microseconds(100 * (i + 1)));
  }
  expect_recovery(trajectory, start + ros::Duration(1), 2000 * 1e-4);
}

// Two publishers with disjoint joints, at stamps that never match.
TEST_F(HostileTest, TwoPublishersWithDisjointJoints) {
  const Quadratic trajectory(model_, 1.1);
  const ros::Time start(5000.0);
  const std::vector<std::string> arm = {"arm1_joint", "arm2_joint"};
  const std::vector<std::string> base = {
      "slider_joint",      "float_joint/x",    "float_joint/y",    "float_joint/z",
      "float_joint/alpha", "float_joint/beta", "float_joint/gamma"};
  std::vector<ros::Publisher> second;
  for (const std::string ns : {"", "/kalman"})
    second.push_back(nh_.advertise<sensor_msgs::JointState>(ns + "/joint_states", 100));
  ASSERT_TRUE(wait_until(
      [&] { return second[0].getNumSubscribers() > 0 && second[1].getNumSubscribers() > 0; }, 10));
  for (int i = 0; i < 200; ++i) {
    const double t = i * kDt;
    for (auto& p : states_)
      p.publish(joint_state_msg(model_, trajectory.at(t), start + ros::Duration(t), false, arm));
    for (auto& p : second)
      p.publish(joint_state_msg(model_, trajectory.at(t + 0.007), start + ros::Duration(t + 0.007),
                                i % 2 == 0, base));
    std::this_thread::sleep_for(std::chrono::milliseconds(4));
  }
  expect_recovery(trajectory, start, 200 * kDt + 0.007);
}

// joint_accelerations whose stamps match no sample, and malformed ones.
TEST_F(HostileTest, AccelerationsWithMismatchedStamps) {
  std::vector<ros::Publisher> accelerations;
  for (const std::string ns : {"", "/kalman"})
    accelerations.push_back(
        nh_.advertise<mb_kinematics_msgs::JointAccelerations>(ns + "/joint_accelerations", 100));
  ASSERT_TRUE(wait_until(
      [&] {
        return accelerations[0].getNumSubscribers() > 0 && accelerations[1].getNumSubscribers() > 0;
      },
      10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the nodes see the publisher
  const Quadratic trajectory(model_, 1.3);
  const ros::Time start(6000.0);
  std::uniform_int_distribution<int> kind(0, 4);
  for (int i = 0; i < 300; ++i) {
    const sensor_msgs::JointState m = valid(trajectory, i, start, i % 2 == 0);
    mb_kinematics_msgs::JointAccelerations a;
    a.header.stamp = m.header.stamp;
    a.name = m.name;
    a.acceleration.assign(m.name.size(), 0.5);
    switch (kind(random_)) {
      case 0:
        a.header.stamp += ros::Duration(1e-3);
        break;
      case 1:
        a.header.stamp = start - ros::Duration(i);
        break;
      case 2:
        a.acceleration[3] = kNaN;
        break;
      case 3:
        a.acceleration.pop_back();
        break;
      default:
        a.name[0] = "no_such_joint";
    }
    for (auto& p : accelerations) p.publish(a);
    send(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
  }
  expect_recovery(trajectory, start, 300 * kDt);
}

// /diagnostics counts each class of dropped, ignored, repaired or waiting input: one message of
// each class raises its counter.
TEST_F(HostileTest, DiagnosticsCountEachClass) {
  std::mutex mutex;
  std::vector<std::map<std::string, std::string>> reports;
  ros::Subscriber sub = nh_.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& status : m->status) {
          if (status.name != "mb_kinematics: Joint state input") continue;
          std::map<std::string, std::string> values;
          for (const auto& kv : status.values) values[kv.key] = kv.value;
          std::lock_guard<std::mutex> lock(mutex);
          reports.push_back(values);
        }
      });
  auto report_count = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return reports.size();
  };
  ASSERT_TRUE(wait_until([&] { return report_count() > 0; }, 5)) << "no /diagnostics";
  std::map<std::string, std::string> before;
  {
    std::lock_guard<std::mutex> lock(mutex);
    before = reports.back();
  }
  std::vector<ros::Publisher> accelerations;
  for (const std::string ns : {"", "/kalman"})
    accelerations.push_back(
        nh_.advertise<mb_kinematics_msgs::JointAccelerations>(ns + "/joint_accelerations", 100));
  ASSERT_TRUE(wait_until([&] { return accelerations[0].getNumSubscribers() > 0; }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Quadratic trajectory(model_, 1.5);
  const ros::Time start(7000.0);
  int i = 0;
  auto next = [&] { return valid(trajectory, i++, start); };
  std::vector<sensor_msgs::JointState> bad;
  bad.push_back(next()), bad.back().position.pop_back();              // unequal lengths
  bad.push_back(next()), bad.back().name[1] = bad.back().name[0];     // a name twice
  bad.push_back(next()), bad.back().position[2] = kNaN;               // NaN
  bad.push_back(next()), bad.back().position[0] = 1e60;               // beyond 1e50
  bad.push_back(next()), bad.back().name.push_back("no_such_joint");  // repaired
  bad.back().position.push_back(0);
  bad.push_back(sensor_msgs::JointState());  // empty (stamp 0 too)
  for (int j = 0; j < 3; ++j) bad.push_back(next());
  bad.push_back(next()), bad.back().position[7] = 1e300;   // an angle: its estimator restarts
  bad.push_back(next()), bad.back().header.stamp = start;  // backwards
  for (const auto& m : bad) {
    send(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  mb_kinematics_msgs::JointAccelerations a;  // refused: unknown name
  a.header.stamp = start + ros::Duration(100);
  a.name = {"no_such_joint"};
  a.acceleration = {1.0};
  for (auto& p : accelerations) p.publish(a);
  for (int j = 0; j < 2; ++j) {  // the first waits for its accelerations in vain: unpaired
    send(next());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const size_t seen = report_count();
  ASSERT_TRUE(wait_until([&] { return report_count() > seen + 1; }, 5));
  std::map<std::string, std::string> after;
  {
    std::lock_guard<std::mutex> lock(mutex);
    after = reports.back();
  }
  for (const char* key :
       {"dropped: arrays of unequal length", "dropped: a name twice", "dropped: NaN or Inf",
        "dropped: magnitude above 1e50", "ignored: empty or no name of the model",
        "ignored: joint_accelerations refused", "repaired: names not in the model ignored",
        "repaired: zero stamp, time of arrival used",
        "repaired: stamp backwards, estimators restarted",
        "repaired: estimate beyond 1e50 or not finite, coordinate restarted",
        "repaired: joint_accelerations missing, estimated"}) {
    ASSERT_TRUE(before.count(key) && after.count(key)) << key << " not on /diagnostics";
    EXPECT_GT(std::stol(after.at(key)), std::stol(before.at(key))) << key;
  }
  EXPECT_NE(after.at("last problem"), "none");
}

// A link name of 30,000 characters (hostile.test's /long_name node, ~publish_markers): the
// markers' body filter once ran std::regex on it and overflowed the stack. The node stays up
// and its markers draw the link's mass center.
TEST_F(HostileTest, LinkNameOf30000CharactersInTheMarkers) {
  std::atomic<long> spheres{0};
  ros::Subscriber sub = nh_.subscribe<visualization_msgs::MarkerArray>(
      "/long_name/body_kinematics/markers", 10,
      [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        for (const auto& marker : m->markers)
          if (marker.ns == "mass_centers") spheres = static_cast<long>(marker.points.size());
      });
  ros::Publisher states = nh_.advertise<sensor_msgs::JointState>("/long_name/joint_states", 10);
  ASSERT_TRUE(
      wait_until([&] { return sub.getNumPublishers() > 0 && states.getNumSubscribers() > 0; }, 10));
  const ros::Time start(8000.0);
  for (int i = 0; i < 20 && spheres == 0; ++i) {
    sensor_msgs::JointState m;
    m.header.stamp = start + ros::Duration(i * kDt);
    m.name = {"turn"};
    m.position = {0.5 * i * kDt};
    m.velocity = {0.5};
    states.publish(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(wait_until([&] { return spheres == 1; }, 5)) << "no marker of the long link";
  EXPECT_TRUE(alive("/long_name/mb_kinematics")) << "the node with the long link name died";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "hostile_test");
  ros::AsyncSpinner spinner(4);
  spinner.start();
  return RUN_ALL_TESTS();
}
