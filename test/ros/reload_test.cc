// ~reload (reload.test): robot_description changed, then /mb_kinematics/reload. A changed model
// is taken (latched lower_body_array and /tf_static republished, body_kinematics of the new
// model, ~get_partial_velocities on it); a broken one is refused with the loader's one-line error
// and the running model stays; reloads while samples stream publish nothing non-finite and nothing
// that is not the kinematics of one of the two models at the sample's state.
#include <mb_kinematics_msgs/GetPartialVelocities.h>
#include <mb_kinematics_msgs/LowerBodyArray.h>
#include <std_srvs/Trigger.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <sstream>

#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr double kTol = 1e-6;
const double kDt = 0.01;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// The test robot with one more body (`extra`, fixed to arm2) and arm2's joint moved: the same
// coordinates, other kinematics.
std::string changed_urdf(const std::string& original) {
  std::string t =
      replace(original, "<link name=\"camera\"/>", "<link name=\"camera\"/><link name=\"extra\"/>");
  t = replace(t, "<origin xyz=\"0.5 0 0\"/><axis xyz=\"0 1 0\"/>",
              "<origin xyz=\"0.7 0.1 0\"/><axis xyz=\"0 1 0\"/>");
  return replace(t, "</robot>",
                 "<joint name=\"extra_joint\" type=\"fixed\"><parent link=\"arm2\"/>"
                 "<child link=\"extra\"/><origin xyz=\"0 0 0.4\"/></joint></robot>");
}

class ReloadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 1000);
    connect(states_, recorder_);
    ASSERT_TRUE(ros::service::waitForService("/mb_kinematics/reload", 10));
  }
  std_srvs::Trigger::Response reload(const std::string& urdf) {
    nh_.setParam("robot_description", urdf);
    std_srvs::Trigger trigger;
    EXPECT_TRUE(ros::service::call("/mb_kinematics/reload", trigger));
    return trigger.response;
  }
  // Samples of the test trajectory at stamps start + i dt, i < n.
  void publish_run(const ros::Time& start, int n) {
    for (int i = 0; i < n; ++i) {
      states_.publish(joint_state_msg(original_, trajectory_.at(i * kDt),
                                      start + ros::Duration(i * kDt), true));
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  mb_kinematics_msgs::LowerBodyArray latched_topology() {
    mb_kinematics_msgs::LowerBodyArray topology;
    EXPECT_TRUE(latched_lower_body_array(nh_, topology));
    return topology;
  }

  ros::NodeHandle nh_;
  const std::string original_text_ = read_text(source_path("test/ros/test_robot.urdf"));
  const std::string changed_text_ = changed_urdf(original_text_);
  mbk::Model original_ = test_model();
  mbk::Model changed_ = mbk::load_urdf_string(changed_text_, "changed");
  Quadratic trajectory_{original_};
  ros::Publisher states_;
  KinematicsRecorder recorder_{nh_, "body_kinematics"};
};

mbk::JointState<double> state_for(const mbk::Model& model, const mbk::JointState<double>& s) {
  mbk::JointState<double> out(model);  // same coordinate names, same order
  out.position = s.position;
  out.velocity = s.velocity;
  out.acceleration = s.acceleration;
  return out;
}

TEST_F(ReloadTest, ToAChangedModelThenToABrokenOne) {
  ASSERT_EQ(changed_.nq, original_.nq);
  ASSERT_EQ(changed_.body_count(), original_.body_count() + 1);
  std::vector<std::string> statics;
  std::mutex mutex;
  ros::Subscriber tf_static = nh_.subscribe<tf2_msgs::TFMessage>(
      "/tf_static", 10, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& t : m->transforms) statics.push_back(t.child_frame_id);
      });

  const std_srvs::Trigger::Response ok = reload(changed_text_);
  EXPECT_TRUE(ok.success) << ok.message;
  EXPECT_EQ(latched_topology().names.size(), static_cast<size_t>(changed_.body_count()));
  EXPECT_TRUE(wait_until(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return std::find(statics.begin(), statics.end(), "extra") != statics.end();
      },
      5))
      << "/tf_static not republished with the new fixed joint";
  const ros::Time start(50.0);
  publish_run(start, 5);
  const ros::Time last = start + ros::Duration(4 * kDt);
  ASSERT_TRUE(recorder_.wait_for(last));
  const mbk::JointState<double> s = state_for(changed_, trajectory_.at(4 * kDt));
  expect_kinematics(recorder_.at(last).back(), changed_, expected_kinematics(changed_, s), kTol);
  mb_kinematics_msgs::GetPartialVelocities partials;  // the service was made anew, on the new model
  partials.request.bodies = {"extra"};
  ASSERT_TRUE(ros::service::call("/mb_kinematics/get_partial_velocities", partials));
  EXPECT_TRUE(partials.response.success) << partials.response.message;

  const std_srvs::Trigger::Response broken = reload("<robot name=\"broken\"><link name=\"a\"/>");
  EXPECT_FALSE(broken.success);
  EXPECT_FALSE(broken.message.empty());
  EXPECT_EQ(broken.message.find('\n'), std::string::npos) << broken.message;
  EXPECT_EQ(latched_topology().names.size(), static_cast<size_t>(changed_.body_count()));
  const ros::Time later(60.0);
  publish_run(later, 5);  // the running (changed) model goes on
  const ros::Time last2 = later + ros::Duration(4 * kDt);
  ASSERT_TRUE(recorder_.wait_for(last2));
  expect_kinematics(recorder_.at(last2).back(), changed_, expected_kinematics(changed_, s), kTol);

  EXPECT_TRUE(reload(original_text_).success);
  EXPECT_EQ(latched_topology().names.size(), static_cast<size_t>(original_.body_count()));
}

// A model that loads but lacks a body of ~per_body_topics ([arm1], reload.test): refused, and
// the running model goes on with its outputs.
TEST_F(ReloadTest, ToAModelWithoutAPerBodyTopicsBody) {
  std::string renamed = original_text_;
  for (size_t at; (at = renamed.find("\"arm1\"")) != std::string::npos;)
    renamed.replace(at, 6, "\"arm9\"");
  const std_srvs::Trigger::Response refused = reload(renamed);
  EXPECT_FALSE(refused.success);
  EXPECT_NE(refused.message.find("arm1"), std::string::npos) << refused.message;
  EXPECT_EQ(latched_topology().names.size(), static_cast<size_t>(original_.body_count()));
  const ros::Time start(70.0);
  publish_run(start, 5);
  const ros::Time last = start + ros::Duration(4 * kDt);
  ASSERT_TRUE(recorder_.wait_for(last));
  expect_kinematics(recorder_.at(last).back(), original_,
                    expected_kinematics(original_, trajectory_.at(4 * kDt)), kTol);
  nh_.setParam("robot_description", original_text_);
}

TEST_F(ReloadTest, WhileSamplesStream) {
  std::atomic<bool> done(false);
  const ros::Time start(100.0);
  const int n = 300;
  std::thread stream([&] {
    publish_run(start, n);
    done = true;
  });
  int reloads = 0;
  while (!done) {
    const bool odd = reloads % 2 == 0;
    EXPECT_TRUE(reload(odd ? changed_text_ : original_text_).success);
    ++reloads;
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
  }
  stream.join();
  EXPECT_GE(reloads, 4);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  // Every message: finite, and the kinematics of one model at its stamp's state.
  size_t checked = 0;
  for (int i = 0; i < n; ++i) {
    const ros::Time stamp = start + ros::Duration(i * kDt);
    for (const auto& msg : recorder_.at(stamp)) {
      const bool is_changed = msg.bodies.size() == static_cast<size_t>(changed_.body_count());
      const mbk::Model& model = is_changed ? changed_ : original_;
      const mbk::JointState<double> s = state_for(model, trajectory_.at(i * kDt));
      SCOPED_TRACE("sample " + std::to_string(i));
      expect_kinematics(msg, model, expected_kinematics(model, s), kTol);
      ++checked;
    }
  }
  // The queues may drop samples on a loaded machine; a quarter at least must come through.
  EXPECT_GT(checked, static_cast<size_t>(n / 4)) << "too few samples published";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "reload_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
