// Shared by the node's integration tests (test/ros/*.test): the test robot, a quadratic joint
// trajectory (which backward_difference, the estimator of the tests' nodes, differentiates
// exactly), the expected kinematics from the core's other formulation (partial velocities,
// doc/method.md 5; the node uses the recursion of doc/method.md 4), and a recorder of
// body_kinematics messages, and a recorder of who publishes which transform on /tf and /tf_static.
// Declared here, compiled once in ros_test_support.cc (the library mbk_ros_test_support,
// test/ros.cmake): the subscriptions' templates instantiated in one object, not in every test.
#pragma once

#include <gtest/gtest.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <mb_kinematics_msgs/LowerBodyArray.h>
#include <nav_msgs/Odometry.h>
#include <ros/message_event.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <sys/wait.h>
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/io/urdf_model.h"

namespace mbk_ros_test {

std::string source_path(const std::string& relative);

mbk::Model test_model();

// q_i(tau) = c0_i + c1_i tau + c2_i tau^2 in every coordinate (mimics: apply_mimics).
struct Quadratic {
  explicit Quadratic(const mbk::Model& model, double phase = 0);
  mbk::JointState<double> at(double tau) const;
  const mbk::Model* model;
  Eigen::VectorXd c0, c1, c2;
};

// A JointState message of `state` for the coordinates `names` (empty: every non-mimic one).
sensor_msgs::JointState joint_state_msg(const mbk::Model& model,
                                        const mbk::JointState<double>& state,
                                        const ros::Time& stamp, bool velocities,
                                        std::vector<std::string> names = {});

mbk::Data<double> expected_kinematics(const mbk::Model& model,
                                      const mbk::JointState<double>& state);

template <typename V>
mbk::Vec3<double> vec(const V& v) {
  return mbk::Vec3<double>(v.x, v.y, v.z);
}

void expect_near(const mbk::Vec3<double>& a, const mbk::Vec3<double>& b, double tol,
                 const std::string& what);

void expect_kinematics(const mb_kinematics_msgs::BodyKinematicsArray& msg, const mbk::Model& model,
                       const mbk::Data<double>& d, double tol);

bool wait_until(const std::function<bool()>& done, double seconds);

// The latched lower_body_array (relative to nh) into `topology`; false if none came in `seconds`.
bool latched_lower_body_array(ros::NodeHandle& nh, mb_kinematics_msgs::LowerBodyArray& topology,
                              double seconds = 5);

// Records every body_kinematics message (callbacks on an AsyncSpinner).
class KinematicsRecorder {
 public:
  KinematicsRecorder(ros::NodeHandle& nh, const std::string& topic);
  bool connected() const;
  // The messages with this stamp, in arrival order.
  std::vector<mb_kinematics_msgs::BodyKinematicsArray> at(const ros::Time& stamp) const;
  size_t count() const;
  mb_kinematics_msgs::BodyKinematicsArray latest() const;  // call when count() > 0
  bool wait_for(const ros::Time& stamp, double seconds = 2.0) const;

 private:
  void on_message(const mb_kinematics_msgs::BodyKinematicsArray& msg);
  mutable std::mutex mutex_;
  std::vector<mb_kinematics_msgs::BodyKinematicsArray> messages_;
  ros::Subscriber sub_;
};

// Waits until `pub` reaches its subscriber and `recorder` its publisher, then lets the
// node see the new subscriber too.
void connect(const ros::Publisher& pub, const KinematicsRecorder& recorder);

// Every transform on /tf and /tf_static, with the node that sent it.
class TfRecorder {
 public:
  explicit TfRecorder(ros::NodeHandle& nh);
  int publishers() const;  // of /tf
  // Per publisher (node name): its transforms as "parent -> child".
  std::map<std::string, std::set<std::string>> by_publisher() const;
  // Per child frame: "publisher: parent" of every transform to it (more than one: a collision).
  std::map<std::string, std::set<std::string>> by_child() const;

 private:
  void on(const ros::MessageEvent<tf2_msgs::TFMessage const>& e);
  mutable std::mutex mutex_;
  std::map<std::string, std::set<std::string>> by_publisher_, by_child_;
  ros::Subscriber tf_, tf_static_;
};

using Key = std::pair<std::string, double>;  // child frame, stamp (0 for /tf_static)

// Every transform on one tf topic, by child frame and stamp (latched: by child frame only).
class Transforms {
 public:
  Transforms(ros::NodeHandle& nh, const std::string& topic, bool latched);
  bool connected() const;
  std::map<Key, geometry_msgs::TransformStamped> get() const;

 private:
  void on(const tf2_msgs::TFMessage& msg);
  bool latched_;
  mutable std::mutex mutex_;
  std::map<Key, geometry_msgs::TransformStamped> transforms_;
  ros::Subscriber sub_;
};

// An odometry message in `frame` of the pose (p, q) and the twist (v, w) in R, which it gives in
// the base's frame (nav_msgs: child_frame_id).
nav_msgs::Odometry odometry_msg(const std::string& frame, const ros::Time& stamp,
                                const mbk::Vec3<double>& p, const Eigen::Quaterniond& q,
                                const mbk::Vec3<double>& v, const mbk::Vec3<double>& w);

// Runs mb_kinematics_node (MBK_NODE_PATH, test/ros.cmake) with `arguments` until it exits;
// returns its exit code (-1 if it did not exit normally) and puts what it printed to stderr into
// `output`.
int run_node(const std::string& arguments, std::string& output);

}  // namespace mbk_ros_test
