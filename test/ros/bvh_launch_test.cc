// launch/bvh.launch on the real recording (bvh_launch.test: test/mocap/131_01.bvh, CMU trial
// 131_01): bvh_player's joint_states carry the model's coordinates, the node's /tf carries every
// segment and body_kinematics every segment, all finite, and the whole-body mass equals the
// launch's body_mass, with the segments the skeleton lacks named in system.missing_segments.
#include <gtest/gtest.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <cmath>
#include <initializer_list>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"

namespace {

bool finite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

template <typename V>
bool finite3(const V& v) {
  return finite({v.x, v.y, v.z});
}

bool finite_body(const mb_kinematics_msgs::BodyKinematics& b) {
  const auto& o = b.pose.orientation;
  return finite3(b.pose.position) && finite({o.x, o.y, o.z, o.w}) && finite3(b.mass_center) &&
         finite3(b.twist.linear) && finite3(b.twist.angular) && finite3(b.accel.linear) &&
         finite3(b.accel.angular);
}

// What the test heard, under one lock.
struct Heard {
  std::mutex mutex;
  std::vector<std::string> joint_state_names;
  std::map<std::string, bool> tf_finite;  // child frame -> every transform to it finite
  std::vector<mb_kinematics_msgs::BodyKinematicsArray> kinematics;
};

class BvhLaunchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle pnh("~");
    ASSERT_TRUE(pnh.getParam("bvh", path_) && pnh.getParam("scale", options_.scale) &&
                pnh.getParam("body_mass", options_.body_mass))
        << "bvh_launch.test sets ~bvh, ~scale and ~body_mass";
    const mbk::BvhFile bvh = mbk::read_bvh(path_);
    model_ = mbk::model_from_bvh(bvh, options_);
    missing_ = mbk::bvh_missing_segments(bvh, options_);
    subs_.push_back(nh_.subscribe<sensor_msgs::JointState>(
        "joint_states", 10, [this](const sensor_msgs::JointState::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(heard_.mutex);
          heard_.joint_state_names = m->name;
        }));
    subs_.push_back(nh_.subscribe<tf2_msgs::TFMessage>(
        "/tf", 100, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(heard_.mutex);
          for (const auto& t : m->transforms) {
            const auto& p = t.transform.translation;
            const auto& q = t.transform.rotation;
            const bool ok = finite({p.x, p.y, p.z, q.x, q.y, q.z, q.w});
            auto it = heard_.tf_finite.emplace(t.child_frame_id, ok).first;
            it->second = it->second && ok;
          }
        }));
    subs_.push_back(nh_.subscribe<mb_kinematics_msgs::BodyKinematicsArray>(
        "body_kinematics", 100, [this](const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(heard_.mutex);
          heard_.kinematics.push_back(*m);
        }));
  }

  // Waits (up to 30 s) until `done` holds for what was heard.
  bool wait(const std::function<bool(const Heard&)>& done) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < end) {
      {
        std::lock_guard<std::mutex> lock(heard_.mutex);
        if (done(heard_)) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  ros::NodeHandle nh_;
  std::string path_;
  mbk::BvhModelOptions options_;
  mbk::Model model_;
  std::vector<std::string> missing_;  // the table's segments the skeleton lacks
  Heard heard_;  // before subs_: destroyed after them, so no callback finds it gone
  std::vector<ros::Subscriber> subs_;
};

TEST_F(BvhLaunchTest, PlayerPublishesTheModelsCoordinates) {
  ASSERT_TRUE(wait([](const Heard& h) { return !h.joint_state_names.empty(); }));
  std::lock_guard<std::mutex> lock(heard_.mutex);
  EXPECT_EQ(heard_.joint_state_names, model_.coordinate_names);
  EXPECT_EQ(model_.nq, 6 + 3 * (model_.body_count() - 1));  // the root's six coordinates too
}

TEST_F(BvhLaunchTest, TfForEverySegmentFinite) {
  ASSERT_TRUE(wait([this](const Heard& h) {
    for (int k = 1; k <= model_.body_count(); ++k)
      if (!h.tf_finite.count(model_.bodies[k].name)) return false;
    return true;
  })) << "not every segment's frame came on /tf";
  std::lock_guard<std::mutex> lock(heard_.mutex);
  for (int k = 1; k <= model_.body_count(); ++k)
    EXPECT_TRUE(heard_.tf_finite[model_.bodies[k].name]) << model_.bodies[k].name;
}

TEST_F(BvhLaunchTest, BodyKinematicsForEverySegmentFiniteWithTheBodyMass) {
  // Some messages into the walk, so that velocities and accelerations are estimated.
  ASSERT_TRUE(wait([](const Heard& h) { return h.kinematics.size() >= 20; }));
  std::lock_guard<std::mutex> lock(heard_.mutex);
  for (const auto& msg : heard_.kinematics) {
    ASSERT_EQ(msg.bodies.size(), static_cast<size_t>(model_.body_count()));
    for (int k = 1; k <= model_.body_count(); ++k) {
      const auto& b = msg.bodies[k - 1];
      EXPECT_EQ(b.name, model_.bodies[k].name);
      EXPECT_TRUE(finite_body(b)) << b.name << " at " << msg.header.stamp;
    }
    ASSERT_TRUE(msg.system.filled);
    EXPECT_NEAR(msg.system.mass, options_.body_mass, 1e-9 * options_.body_mass);
    EXPECT_EQ(msg.system.missing_segments, missing_);
    EXPECT_TRUE(finite3(msg.system.mass_center) && finite3(msg.system.velocity) &&
                finite3(msg.system.acceleration) && finite3(msg.system.angular_momentum));
  }
  // The skeleton walks: the whole-body mass center moves.
  const auto& first = heard_.kinematics.front().system.mass_center;
  const auto& last = heard_.kinematics.back().system.mass_center;
  EXPECT_GT(std::hypot(last.x - first.x, last.y - first.y, last.z - first.z), 1e-3);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bvh_launch_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
