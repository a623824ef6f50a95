// ~missing_coordinates on test_robot.urdf (missing.test): every joint but arm2_joint is sent, so
// arm2, the fixed tool on it and the finger (a mimic of arm2_joint) cannot be placed.
//   skip (the default): the other bodies are published from the first sample on, exactly; arm2,
//     tool and finger are not on /tf, body_kinematics or their per-body topics; the system is
//     not filled; a warning on /rosout and /diagnostics name arm2_joint; when arm2_joint comes,
//     they join; when it stops for more than ~max_sample_gap, they are left out again.
//   zero: every body, computed with arm2_joint = 0 (finger = 2 * 0 + 0.1), named as invented.
//   wait: nothing until arm2_joint has come.
// A bad value ends the node at start, naming the allowed ones.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TwistStamped.h>
#include <mb_kinematics_msgs/GetPartialVelocities.h>
#include <rosgraph_msgs/Log.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;
constexpr double kDt = 0.02;
const char kMissing[] = "arm2_joint";
const std::vector<std::string> kPlaced = {"slider", "floater", "camera", "arm1"};  // 1..4

std::vector<std::string> all_but_arm2(const mbk::Model& model) {
  std::vector<std::string> names;
  for (const std::string& n : model.coordinate_names)
    if (n != kMissing && n != "finger_joint") names.push_back(n);  // finger: a mimic
  return names;
}

// The messages a node sends about itself: /rosout lines, its /diagnostics status, /tf frames.
class Watch {
 public:
  Watch(ros::NodeHandle& nh, const std::string& node) : node_(node) {
    subs_.push_back(nh.subscribe<rosgraph_msgs::Log>(
        "/rosout", 1000, [this](const rosgraph_msgs::Log::ConstPtr& m) {
          if (m->name != node_ || m->level != rosgraph_msgs::Log::WARN) return;
          std::lock_guard<std::mutex> lock(mutex_);
          warnings_.push_back(m->msg);
        }));
    subs_.push_back(nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
          for (const auto& s : m->status) {
            if (s.name != node_.substr(1) + ": Joint state input") continue;
            std::lock_guard<std::mutex> lock(mutex_);
            diagnostics_ = s;
            ++reports_;
          }
        }));
    subs_.push_back(nh.subscribe<tf2_msgs::TFMessage>(
        "/tf", 1000, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& t : m->transforms) frames_[t.header.stamp].insert(t.child_frame_id);
        }));
  }
  // Warnings that contain `text`.
  int warnings(const std::string& text) const {
    std::lock_guard<std::mutex> lock(mutex_);
    int n = 0;
    for (const std::string& w : warnings_) n += w.find(text) != std::string::npos;
    return n;
  }
  std::set<std::string> frames(const ros::Time& stamp) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = frames_.find(stamp);
    return it == frames_.end() ? std::set<std::string>() : it->second;
  }
  // The next /diagnostics status of the node (a report that began after this call).
  diagnostic_msgs::DiagnosticStatus next_diagnostics() const {
    long seen;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      seen = reports_;
    }
    EXPECT_TRUE(wait_until(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          return reports_ > seen + 1;
        },
        5))
        << "no /diagnostics from " << node_;
    std::lock_guard<std::mutex> lock(mutex_);
    return diagnostics_;
  }

 private:
  std::string node_;
  mutable std::mutex mutex_;
  std::vector<std::string> warnings_;
  std::map<ros::Time, std::set<std::string>> frames_;
  diagnostic_msgs::DiagnosticStatus diagnostics_;
  long reports_ = 0;
  std::vector<ros::Subscriber> subs_;
};

std::string value(const diagnostic_msgs::DiagnosticStatus& status, const std::string& key) {
  for (const auto& kv : status.values)
    if (kv.key == key) return kv.value;
  return "(no key '" + key + "')";
}

// The body_kinematics bodies, by name, against the core's partial-velocity formulation.
void expect_bodies(const mb_kinematics_msgs::BodyKinematicsArray& msg, const mbk::Model& model,
                   const mbk::JointState<double>& state, const std::vector<std::string>& names) {
  ASSERT_EQ(msg.bodies.size(), names.size());
  const mbk::Data<double> d = expected_kinematics(model, state);
  for (size_t i = 0; i < names.size(); ++i) {
    const auto& b = msg.bodies[i];
    const int k = model.body_index(names[i]);
    EXPECT_EQ(b.name, names[i]);
    EXPECT_EQ(b.index, static_cast<uint32_t>(k));
    EXPECT_EQ(b.lower_body, static_cast<uint32_t>(model.bodies[k].lower));
    expect_near(vec(b.pose.position), d.origin[k], kTol, names[i] + " origin");
    expect_near(vec(b.mass_center), d.mass_center[k], kTol, names[i] + " mass center");
    expect_near(vec(b.twist.angular), d.omega[k], kTol, names[i] + " omega");
    expect_near(vec(b.twist.linear), d.mass_center_velocity[k], kTol, names[i] + " velocity");
    expect_near(vec(b.accel.angular), d.alpha[k], kTol, names[i] + " alpha");
    expect_near(vec(b.accel.linear), d.mass_center_acceleration[k], kTol,
                names[i] + " acceleration");
  }
}

class MissingTest : public ::testing::Test {
 protected:
  void start(const std::string& ns) {
    nh_ = ros::NodeHandle(ns);
    states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 100);
    recorder_ = std::make_unique<KinematicsRecorder>(nh_, "body_kinematics");
    watch_ = std::make_unique<Watch>(nh_, "/" + ns + "/mb_kinematics");
    connect(states_, *recorder_);
  }
  // Samples i in [from, to) of the trajectory at start + i dt, of `names` (empty: every joint).
  void send(const Quadratic& trajectory, const ros::Time& start, int from, int to,
            const std::vector<std::string>& names) {
    for (int i = from; i < to; ++i) {
      states_.publish(joint_state_msg(model_, trajectory.at(i * kDt),
                                      start + ros::Duration(i * kDt), false, names));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  // The node's next /diagnostics status while samples [from, from + 150) stream in (its
  // summary speaks of the input only while some comes).
  diagnostic_msgs::DiagnosticStatus diagnostics_while_sending(
      const Quadratic& trajectory, const ros::Time& start, int from,
      const std::vector<std::string>& names) {
    std::thread sender([&] { send(trajectory, start, from, from + 150, names); });
    const diagnostic_msgs::DiagnosticStatus status = watch_->next_diagnostics();
    sender.join();
    return status;
  }
  const mbk::Model model_ = test_model();
  ros::NodeHandle nh_;
  ros::Publisher states_;
  std::unique_ptr<KinematicsRecorder> recorder_;
  std::unique_ptr<Watch> watch_;
};

TEST_F(MissingTest, SkipPublishesThePlacedBodiesAndTheOthersWhenTheirJointComes) {
  start("skip");
  std::atomic<int> arm1_twists{0}, arm2_twists{0}, finger_twists{0};
  ros::Subscriber arm1_twist = nh_.subscribe<geometry_msgs::TwistStamped>(
      "body/arm1/twist", 100, [&](const geometry_msgs::TwistStamped::ConstPtr&) { ++arm1_twists; });
  ros::Subscriber arm2_twist = nh_.subscribe<geometry_msgs::TwistStamped>(
      "body/arm2/twist", 100, [&](const geometry_msgs::TwistStamped::ConstPtr&) { ++arm2_twists; });
  ros::Subscriber finger_twist = nh_.subscribe<geometry_msgs::TwistStamped>(
      "body/finger/twist", 100,
      [&](const geometry_msgs::TwistStamped::ConstPtr&) { ++finger_twists; });
  ASSERT_TRUE(wait_until([&] { return finger_twist.getNumPublishers() > 0; }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));

  const Quadratic trajectory(model_, 1.0);
  const ros::Time start(1000.0);
  auto stamp = [&](int i) { return start + ros::Duration(i * kDt); };
  send(trajectory, start, 0, 6, all_but_arm2(model_));
  ASSERT_TRUE(recorder_->wait_for(stamp(5)));
  // From the first sample on: /tf of the placed moving bodies (camera is fixed: /tf_static).
  ASSERT_TRUE(wait_until([&] { return !watch_->frames(stamp(5)).empty(); }, 2));
  for (int i : {0, 5}) {
    EXPECT_EQ(watch_->frames(stamp(i)), (std::set<std::string>{"slider", "floater", "arm1"}))
        << "sample " << i;
  }
  for (int i = 2; i < 6; ++i) {  // backward_difference: accelerations from the third sample
    const auto msgs = recorder_->at(stamp(i));
    ASSERT_EQ(msgs.size(), 1u) << "sample " << i;
    expect_bodies(msgs[0], model_, trajectory.at(i * kDt), kPlaced);
    EXPECT_FALSE(msgs[0].system.filled) << "a system of 4 bodies out of 7 passed for the whole";
  }
  // ~get_partial_velocities: the bodies left out are refused, naming why; every body: the 4.
  ros::ServiceClient client = nh_.serviceClient<mb_kinematics_msgs::GetPartialVelocities>(
      "mb_kinematics/get_partial_velocities");
  mb_kinematics_msgs::GetPartialVelocities srv;
  srv.request.bodies = {"arm1", "finger"};
  ASSERT_TRUE(client.call(srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("'finger' is left out"), std::string::npos)
      << srv.response.message;
  srv.request.bodies.clear();
  ASSERT_TRUE(client.call(srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ASSERT_EQ(srv.response.partials.size(), kPlaced.size());
  for (size_t i = 0; i < kPlaced.size(); ++i) EXPECT_EQ(srv.response.partials[i].body, kPlaced[i]);
  EXPECT_GT(arm1_twists.load(), 0);
  EXPECT_EQ(arm2_twists.load(), 0);
  EXPECT_EQ(finger_twists.load(), 0);
  // Named once, on /rosout and /diagnostics.
  ASSERT_TRUE(wait_until([&] { return watch_->warnings(kMissing) > 0; }, 3));
  EXPECT_EQ(watch_->warnings(kMissing), 1) << "named more than once";
  EXPECT_EQ(watch_->warnings("arm2, tool, finger"), 1) << "the bodies left out not named";
  diagnostic_msgs::DiagnosticStatus status =
      diagnostics_while_sending(trajectory, start, 6, all_but_arm2(model_));
  EXPECT_EQ(value(status, "joints never received"), kMissing);
  EXPECT_EQ(value(status, "bodies left out"), "arm2, tool, finger");
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(status.message.find(kMissing), std::string::npos) << status.message;

  // arm2_joint comes: its bodies join, exactly, once its estimates have the three samples
  // they need (the others go on meanwhile), and the system is whole again.
  send(trajectory, start, 156, 162, {});
  ASSERT_TRUE(recorder_->wait_for(stamp(161)));
  std::vector<std::string> every;
  for (int k = 1; k <= model_.body_count(); ++k) every.push_back(model_.bodies[k].name);
  for (int i = 156; i < 162; ++i) {
    const bool joined = i >= 158;  // arm2_joint's third sample on
    const auto msgs = recorder_->at(stamp(i));
    ASSERT_EQ(msgs.size(), 1u) << "sample " << i;
    expect_bodies(msgs[0], model_, trajectory.at(i * kDt), joined ? every : kPlaced);
    EXPECT_EQ(msgs[0].system.filled, joined) << "sample " << i;
    std::set<std::string> frames = {"slider", "floater", "arm1"};
    if (joined) frames.insert({"arm2", "finger"});
    EXPECT_EQ(watch_->frames(stamp(i)), frames) << "sample " << i;
  }
  ASSERT_TRUE(wait_until([&] { return arm2_twists > 0 && finger_twists > 0; }, 2));
  status = diagnostics_while_sending(trajectory, start, 162, {});
  EXPECT_EQ(value(status, "joints never received"), "none");
  EXPECT_EQ(value(status, "bodies left out"), "none");
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::OK) << status.message;

  // arm2_joint stops for more than ~max_sample_gap (1 s): stale, its bodies left out again.
  const ros::Time later = start + ros::Duration(10.0);  // arm2_joint's last: start + 6.22 s
  send(trajectory, later, 0, 4, all_but_arm2(model_));
  ASSERT_TRUE(recorder_->wait_for(later + ros::Duration(3 * kDt)));
  EXPECT_EQ(watch_->frames(later), (std::set<std::string>{"slider", "floater", "arm1"}));
  const auto msgs = recorder_->at(later + ros::Duration(3 * kDt));
  ASSERT_EQ(msgs.size(), 1u);
  expect_bodies(msgs[0], model_, trajectory.at(3 * kDt), kPlaced);
  ASSERT_TRUE(wait_until([&] { return watch_->warnings("~max_sample_gap: arm2_joint") > 0; }, 3));
  status = watch_->next_diagnostics();
  EXPECT_EQ(value(status, "joints stale (no sample for ~max_sample_gap)"), kMissing);
  EXPECT_EQ(value(status, "bodies left out"), "arm2, tool, finger");
}

TEST_F(MissingTest, ZeroTakesTheMissingJointAsZeroAndSaysSo) {
  start("zero");
  const Quadratic trajectory(model_, 2.0);
  const ros::Time start(2000.0);
  send(trajectory, start, 0, 4, all_but_arm2(model_));
  const ros::Time last = start + ros::Duration(3 * kDt);
  ASSERT_TRUE(recorder_->wait_for(last));
  mbk::JointState<double> zeroed = trajectory.at(3 * kDt);
  const int q = model_.coordinate_index(kMissing);
  zeroed.position[q] = zeroed.velocity[q] = zeroed.acceleration[q] = 0;
  mbk::apply_mimics(model_, zeroed);  // finger: 2 * 0 + 0.1
  std::vector<std::string> every;
  for (int k = 1; k <= model_.body_count(); ++k) every.push_back(model_.bodies[k].name);
  const auto msgs = recorder_->at(last);
  ASSERT_EQ(msgs.size(), 1u);
  expect_bodies(msgs[0], model_, zeroed, every);
  ASSERT_TRUE(wait_until([&] { return watch_->warnings("taken as 0") > 0; }, 3));
  EXPECT_EQ(watch_->warnings(kMissing), 1);
  const diagnostic_msgs::DiagnosticStatus status =
      diagnostics_while_sending(trajectory, start, 4, all_but_arm2(model_));
  EXPECT_EQ(value(status, "joints never received"), kMissing);
  EXPECT_EQ(value(status, "bodies from invented or held values"), "arm2, tool, finger");
  EXPECT_NE(value(status, "invented: joints never received taken as 0"), "0");
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(status.message.find("taken as 0"), std::string::npos) << status.message;
}

TEST_F(MissingTest, WaitPublishesNothingUntilEveryJointHasCome) {
  start("wait");
  const Quadratic trajectory(model_, 3.0);
  const ros::Time start(3000.0);
  send(trajectory, start, 0, 4, all_but_arm2(model_));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(recorder_->count(), 0u) << "published with arm2_joint missing";
  diagnostic_msgs::DiagnosticStatus status = watch_->next_diagnostics();
  EXPECT_EQ(value(status, "joints never received"), kMissing);
  EXPECT_NE(value(status, "waiting: joints never received"), "0");
  send(trajectory, start, 4, 7, {});
  const ros::Time last = start + ros::Duration(6 * kDt);
  ASSERT_TRUE(recorder_->wait_for(last));
  expect_kinematics(recorder_->at(last).at(0), model_,
                    expected_kinematics(model_, trajectory.at(6 * kDt)), kTol);
}

TEST(MissingStartup, BadValueExitsNamingTheAllowedOnes) {
  ros::NodeHandle nh;
  std::string urdf;
  ASSERT_TRUE(nh.getParam("/skip/robot_description", urdf));
  nh.setParam("/bad/robot_description", urdf);
  std::string output;
  EXPECT_GT(run_node("__ns:=/bad __name:=bad_node _missing_coordinates:=drop", output), 0);
  EXPECT_NE(output.find("missing_coordinates: unknown value 'drop' (allowed: skip, wait, zero)"),
            std::string::npos)
      << output;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "missing_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
