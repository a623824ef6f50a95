// mb_kinematics_node: a thin adapter from joint_states to the core (doc/method.md 8), in the manner
// of robot_state_publisher: parameters read in one place, one callback per sample, throttled
// warnings that say what was wrong.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TransformStamped.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <mb_kinematics_msgs/JointAccelerations.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <array>
#include <chrono>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/derivative_estimator.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/ros/joint_state_input.h"
#include "mb_kinematics/ros/kinematics_markers.h"
#include "mb_kinematics/ros/node_params.h"

namespace mbk_ros {

// The model the parameters name: ~lower_body_array, else ~model, else robot_description (URDF).
// Euler-parameter joints get coordinate-derivative speeds. Throws std::invalid_argument.
mbk::Model load_node_model(const NodeParams& params);

class KinematicsNode {
 public:
  // Reads the parameters, loads the model, logs the lower body arrays table, advertises and
  // subscribes. Throws std::invalid_argument (with a one-line reason) when it cannot start.
  KinematicsNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  void on_joint_states(const sensor_msgs::JointStateConstPtr& msg);
  void on_joint_accelerations(const mb_kinematics_msgs::JointAccelerationsConstPtr& msg);
  void process(const sensor_msgs::JointState& msg);  // one sample: merge, compute, publish
  bool report(const JointStateInput::Update& update);
  mbk::Level wanted_level() const;
  const AccelerationSample* accelerations_at(double t) const;
  void publish_static_tf();
  void publish_tf(const ros::Time& stamp);
  bool publish_kinematics(const ros::Time& stamp, mbk::Level level);
  void fill_kinematics_msg(const ros::Time& stamp);
  void publish_markers();
  void advertise();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  NodeParams params_;
  mbk::Model model_;
  std::string frame_;  // R
  JointStateInput input_;
  mbk::JointState<double> state_;
  mbk::JointState<double> previous_state_;  // the last published sample, for the residual
  double previous_stamp_ = -1;              // its stamp; < 0: none
  mbk::Data<double> data_;

  ros::NodeHandle nh_, pnh_;
  ros::Subscriber joint_states_sub_, accelerations_sub_;
  ros::Publisher lower_body_pub_, kinematics_pub_, markers_pub_;
  std::vector<ros::Publisher> twist_pubs_, accel_pubs_;  // index k; empty without per-body topics
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  std::vector<int> moving_;  // bodies on joints with coordinates: their tf goes to /tf
  std::vector<geometry_msgs::TransformStamped> transforms_;  // one per moving body
  std::vector<ros::Time> last_tf_stamp_;                     // per moving body
  mb_kinematics_msgs::BodyKinematicsArray kinematics_msg_;
  GlyphStyle marker_style_;  // ~publish_markers: the picture's style
  std::array<AutoScale, GlyphQuantity::kCount> marker_scales_;  // and its arrows' auto-scales

  sensor_msgs::JointStateConstPtr pending_;       // waits for its joint_accelerations
  std::deque<AccelerationSample> accelerations_;  // the latest few, by stamp

  diagnostic_updater::Updater updater_;
  ros::Timer diagnostics_timer_;
  struct Counters {
    long received = 0, dropped = 0, incomplete = 0, published = 0;
    double update_seconds = 0, max_update_seconds = 0;
    double max_residual = 0;  // mbk::prediction_residual, over the samples
  } total_, window_;
  std::chrono::steady_clock::time_point window_start_;
  std::string last_problem_;
};

}  // namespace mbk_ros
