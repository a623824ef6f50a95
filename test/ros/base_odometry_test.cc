// ~base_odometry (base_odometry.test): body_kinematics of both nodes against the floating URDF
// (test_robot_floating.urdf: the base on a floating joint, 1-2-3 angles) evaluated by the core's
// partial-velocity formulation, with the odometry made from that model's base. The base turns
// about one fixed axis at a constant angular acceleration and accelerates uniformly, so its
// velocities in R are linear in time and the nodes' backward_difference estimates the base's
// acceleration exactly. Then bad odometry: NaN, another frame_id, odometry too new and too old,
// each counted on /diagnostics.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Odometry.h>
#include <ros/message_event.h>

#include <cmath>

#include "mb_kinematics/core/kinematics_double.h"
#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;
const double kDt = 0.02;

// The input counters of /mb_kinematics on /diagnostics (doc/node.md: a key per class of input).
class InputCounters {
 public:
  explicit InputCounters(ros::NodeHandle& nh)
      : sub_(nh.subscribe("/diagnostics", 10, &InputCounters::on, this)) {}
  // The value of `key` in the second report from now (made after what came before the call;
  // -1: none within 5 s).
  long next(const std::string& key) {
    const int seen = reports();
    if (!wait_until([&] { return reports() > seen + 1; }, 5)) return -1;
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_.count(key) ? std::stol(latest_.at(key)) : -1;
  }

 private:
  int reports() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return reports_;
  }
  void on(const ros::MessageEvent<diagnostic_msgs::DiagnosticArray const>& e) {
    if (e.getPublisherName() != "/mb_kinematics") return;
    for (const auto& status : e.getMessage()->status) {
      if (status.name.find("Joint state input") == std::string::npos) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& kv : status.values) latest_[kv.key] = kv.value;
      ++reports_;
    }
  }
  mutable std::mutex mutex_;
  std::map<std::string, std::string> latest_;
  int reports_ = 0;
  ros::Subscriber sub_;
};

class BaseOdometryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    floating_.frame = "odom";  // R is the odometry's frame
    states_ = nh_.advertise<sensor_msgs::JointState>("/joint_states", 100);
    odom_ = nh_.advertise<nav_msgs::Odometry>("/odom", 100);
    ASSERT_TRUE(wait_until([&] { return odom_.getNumSubscribers() >= 2; }, 10));
    odom_.publish(odometry(0, ros::Time(1.0)));  // R is known: the nodes advertise their outputs
    connect(states_, recorder_);
    connect(states_, floating_recorder_);
  }
  // The floating model's state at tau: the base on root/x y z (quadratic) and root/gamma
  // (quadratic; alpha, beta constant: one fixed axis), the other coordinates on `joints`. With
  // uniform_ the base's x y z and gamma are linear in tau: a constant velocity and a constant
  // angular velocity about a fixed axis, which slerp and linear interpolation follow exactly.
  mbk::JointState<double> full_state(double tau) const {
    mbk::JointState<double> s(floating_);
    const mbk::JointState<double> j = joints_.at(tau);
    const int n = floating_.nq - model_.nq;
    s.position.tail(model_.nq) = j.position;
    s.velocity.tail(model_.nq) = j.velocity;
    s.acceleration.tail(model_.nq) = j.acceleration;
    const double c0[6] = {0.4, -0.3, 0.2, 0.3, -0.4, 0.5}, c1[6] = {0.5, 0.2, -0.1, 0, 0, 0.7},
                 c2[6] = {0.3, -0.6, 0.2, 0, 0, -0.9};
    for (int i = 0; i < n; ++i) {
      const double c2i = uniform_ ? 0 : c2[i];
      s.position[i] = c0[i] + c1[i] * tau + c2i * tau * tau;
      s.velocity[i] = c1[i] + 2 * c2i * tau;
      s.acceleration[i] = 2 * c2i;
    }
    return s;
  }
  nav_msgs::Odometry odometry(double tau, const ros::Time& stamp) const {
    mbk::Data<double> d(floating_);
    mbk::forward_kinematics(floating_, full_state(tau), d);
    return odometry_msg("odom", stamp, d.origin[1], Eigen::Quaterniond(d.rotation[1]),
                        d.origin_velocity[1], d.omega[1]);
  }
  // n samples from `start` (tau = i dt): odometry one step ahead of joint_states, as a faster
  // odometry source would be. `odometry_shift` moves the odometry's stamps (and so its tau).
  void publish_run(const ros::Time& start, int n, double odometry_shift = 0,
                   const std::function<void(int, nav_msgs::Odometry&)>& spoil = nullptr) {
    for (int i = -1; i < n; ++i) {
      const double tau = (i + 1) * kDt + odometry_shift;
      nav_msgs::Odometry o = odometry(tau, start + ros::Duration(tau));
      if (spoil) spoil(i + 1, o);
      odom_.publish(o);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      if (i >= 0)
        states_.publish(
            joint_state_msg(model_, joints_.at(i * kDt), start + ros::Duration(i * kDt), true));
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  // Every message recorded in [start, start + n dt): finite and equal to the expected
  // kinematics; returns how many.
  size_t check_run(const ros::Time& start, int n, const KinematicsRecorder& recorder) const {
    size_t count = 0;
    for (int i = 0; i < n; ++i) {
      for (const auto& msg : recorder.at(start + ros::Duration(i * kDt))) {
        SCOPED_TRACE("sample " + std::to_string(i));
        expect_kinematics(msg, floating_, expected_kinematics(floating_, full_state(i * kDt)),
                          kTol);
        ++count;
      }
    }
    return count;
  }

  ros::NodeHandle nh_;
  bool uniform_ = false;
  mbk::Model model_ = test_model();
  mbk::Model floating_ = mbk::load_urdf_file(source_path("test/ros/test_robot_floating.urdf"));
  Quadratic joints_{model_};
  ros::Publisher states_, odom_;
  KinematicsRecorder recorder_{nh_, "/body_kinematics"};
  KinematicsRecorder floating_recorder_{nh_, "/floating/body_kinematics"};
};

TEST_F(BaseOdometryTest, AbsoluteKinematicsInTheOdometryFrame) {
  TfRecorder tf(nh_);
  ASSERT_TRUE(wait_until([&] { return tf.publishers() >= 2; }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const ros::Time start(100.0);
  const int n = 10;
  publish_run(start, n);
  ASSERT_TRUE(recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  ASSERT_TRUE(floating_recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  EXPECT_GE(check_run(start, n, recorder_), static_cast<size_t>(n - 3));
  EXPECT_GE(check_run(start, n, floating_recorder_), static_cast<size_t>(n - 3));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  std::map<std::string, std::set<std::string>> parents = tf.by_publisher();
  EXPECT_EQ(parents["/mb_kinematics"].count("odom -> base_link"), 0u) << "~publish_base_tf false";
  EXPECT_EQ(parents["/mb_kinematics"].count("base_link -> slider"), 1u);
  EXPECT_EQ(parents["/floating/mb_kinematics"].count("odom -> f/base_link"), 1u);
  EXPECT_EQ(parents["/floating/mb_kinematics"].count("f/base_link -> f/slider"), 1u);
}

// Odometry stamped half a period after each joint sample and sent after it. Each
// sample waits (~base_odometry_wait, default) for the odometry after its stamp and takes the base
// interpolated between the two around it: on a base motion that slerp and lerp follow exactly,
// the published base (tf and every body of body_kinematics) is the exact one to 1e-9 m.
TEST_F(BaseOdometryTest, OdometryHalfAPeriodLateIsInterpolated) {
  uniform_ = true;
  Transforms base_tf(nh_, "/tf", false);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const ros::Time start(150.0);
  const int n = 12;
  odom_.publish(odometry(-0.5 * kDt, start - ros::Duration(0.5 * kDt)));
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  for (int i = 0; i < n; ++i) {
    const ros::Time stamp = start + ros::Duration(i * kDt);
    states_.publish(joint_state_msg(model_, joints_.at(i * kDt), stamp, true));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // the odometry comes later
    odom_.publish(odometry((i + 0.5) * kDt, stamp + ros::Duration(0.5 * kDt)));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  ASSERT_TRUE(floating_recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const std::map<Key, geometry_msgs::TransformStamped> tf = base_tf.get();
  double position = 0, rotation = 0;  // the largest errors of the published poses
  size_t poses = 0;
  for (int i = 0; i < n; ++i) {
    const ros::Time stamp = start + ros::Duration(i * kDt);
    const mbk::Data<double> d = expected_kinematics(floating_, full_state(i * kDt));
    const auto add = [&](const mbk::Vec3<double>& p, const Eigen::Quaterniond& q, int k) {
      position = std::max(position, (p - d.origin[k]).norm());
      rotation = std::max(rotation, (q.toRotationMatrix() - d.rotation[k]).norm());
      ++poses;
    };
    const auto t = tf.find({"f/base_link", stamp.toSec()});
    EXPECT_NE(t, tf.end()) << "no odom -> f/base_link at sample " << i;
    if (t != tf.end()) {
      const auto& r = t->second.transform.rotation;
      add(vec(t->second.transform.translation), Eigen::Quaterniond(r.w, r.x, r.y, r.z), 1);
    }
    for (const KinematicsRecorder* recorder : {&recorder_, &floating_recorder_}) {
      const auto msgs = recorder->at(stamp);
      if (i < 3 && msgs.empty()) continue;  // the base's acceleration is not estimated yet
      ASSERT_EQ(msgs.size(), 1u) << "sample " << i << ": published once, none dropped";
      for (int k = 1; k <= floating_.body_count(); ++k) {
        const auto& o = msgs[0].bodies.at(k - 1).pose.orientation;
        add(vec(msgs[0].bodies[k - 1].pose.position), Eigen::Quaterniond(o.w, o.x, o.y, o.z), k);
      }
      SCOPED_TRACE("sample " + std::to_string(i));
      expect_kinematics(msgs[0], floating_, d, kTol);  // the rest of the kinematics as well
    }
  }
  std::printf("  %zu poses: %.1e m, %.1e (rotation matrix difference)\n", poses, position,
              rotation);
  EXPECT_LT(position, 1e-9);
  EXPECT_LT(rotation, 1e-9);
}

TEST_F(BaseOdometryTest, NaNAndAnotherFrameAreRefused) {
  InputCounters counters(nh_);
  const char* const kRefused = "ignored: base odometry refused";
  const long before = counters.next(kRefused);
  ASSERT_GE(before, 0) << kRefused << " not on /diagnostics";
  const ros::Time start(200.0);
  const int n = 12;
  publish_run(start, n, 0, [](int i, nav_msgs::Odometry& o) {
    if (i == 4) o.twist.twist.linear.y = std::nan("");
    if (i == 5) o.pose.pose.orientation.w = std::numeric_limits<double>::infinity();
    if (i == 8) {
      o.header.frame_id = "map";
      o.pose.pose.position.x += 100;
    }
  });
  ASSERT_TRUE(recorder_.wait_for(start + ros::Duration((n - 1) * kDt)));
  // Samples next to a refused odometry message use the neighbours (interpolated or held within
  // the gap): nothing published differs from the kinematics of the true motion by more than
  // the interpolation of its twist allows, and nothing is non-finite.
  for (int i = 0; i < n; ++i)
    for (const auto& msg : recorder_.at(start + ros::Duration(i * kDt)))
      for (const auto& b : msg.bodies) {
        EXPECT_EQ(msg.header.frame_id, "odom");
        EXPECT_TRUE(std::isfinite(b.accel.linear.x + b.accel.linear.y + b.accel.linear.z +
                                  b.twist.linear.x + b.twist.linear.y + b.twist.linear.z +
                                  b.pose.position.x + b.pose.position.y + b.pose.position.z))
            << b.name << " sample " << i;
        EXPECT_LT(std::abs(b.pose.position.x), 10.0) << "the 'map' message was used";
      }
  const ros::Time later(210.0);
  publish_run(later, 8);  // the node goes on
  ASSERT_TRUE(recorder_.wait_for(later + ros::Duration(7 * kDt)));
  EXPECT_GE(check_run(later, 8, recorder_), 4u);
  EXPECT_EQ(counters.next(kRefused), before + 3) << "NaN, Inf and 'map': each counted";
}

TEST_F(BaseOdometryTest, OdometryTooNewOrTooOldPublishesNothing) {
  InputCounters counters(nh_);
  const char* const kDropped = "dropped: no base odometry within the gap";
  const long before = counters.next(kDropped);
  ASSERT_GE(before, 0) << kDropped << " not on /diagnostics";
  const ros::Time start(300.0);
  publish_run(start, 10, 1.0);  // odometry 1 s ahead of the samples (gap 0.2 s)
  const ros::Time old(400.0);
  publish_run(old, 10, -1.0);  // odometry 1 s behind
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  for (int i = 0; i < 10; ++i) {
    EXPECT_TRUE(recorder_.at(start + ros::Duration(i * kDt)).empty()) << "too new, sample " << i;
    EXPECT_TRUE(recorder_.at(old + ros::Duration(i * kDt)).empty()) << "too old, sample " << i;
  }
  const ros::Time later(500.0);
  publish_run(later, 8);  // the node goes on
  ASSERT_TRUE(recorder_.wait_for(later + ros::Duration(7 * kDt)));
  EXPECT_GE(check_run(later, 8, recorder_), 4u);
  EXPECT_EQ(counters.next(kDropped), before + 20) << "every sample of both runs dropped";
}

// A wait out of range or an extrapolate flag that is no bool: the node says which and exits.
TEST(BaseOdometryParams, BadWaitOrExtrapolateExitsNonZero) {
  ros::NodeHandle nh;
  std::string urdf;
  ASSERT_TRUE(nh.getParam("/robot_description", urdf));
  nh.setParam("/bad_wait/robot_description", urdf);
  std::string output;
  EXPECT_GT(
      run_node("__ns:=/bad_wait __name:=n _base_odometry:=odom _base_odometry_wait:=-0.5", output),
      0);
  EXPECT_NE(output.find("base_odometry_wait must be in [0, 10]"), std::string::npos) << output;
  output.clear();
  EXPECT_GT(run_node("__ns:=/bad_wait __name:=m _base_odometry:=odom "  // its own parameters
                     "_base_odometry_extrapolate:=sometimes",
                     output),
            0);
  EXPECT_NE(output.find("base_odometry_extrapolate must be true or false"), std::string::npos)
      << output;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "base_odometry_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
