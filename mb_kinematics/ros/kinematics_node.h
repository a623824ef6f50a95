// mb_kinematics_node: a thin adapter from joint_states to the core (doc/method.md 8; doc/node.md),
// in the manner of robot_state_publisher: parameters read in one place, one callback
// per sample, throttled warnings that say what was wrong. It keeps the input (subscriptions and
// NodeInput: node_input.h), the pairing with joint_accelerations (in JointStateInput) and the
// dispatch to its outputs (outputs/output_table.cc); the outputs publish.
#pragma once

#include <mb_kinematics_msgs/JointAccelerations.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/ros/immediate_callback_queue.h"
#include "mb_kinematics/ros/node_input.h"
#include "mb_kinematics/ros/node_params.h"
#include "mb_kinematics/ros/outputs/output.h"
#include "mb_kinematics/ros/publish_rate.h"

namespace mbk_ros {

class KinematicsNode {
 public:
  // Reads the parameters, loads the model, logs the lower body arrays table, advertises and
  // subscribes. Throws std::invalid_argument (with a one-line reason) when it cannot start.
  KinematicsNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  using Outputs = std::vector<std::unique_ptr<Output>>;

  // An input subscription on queue_, with TCP_NODELAY.
  template <typename M>
  ros::Subscriber subscribe(const std::string& topic,
                            void (KinematicsNode::*callback)(const boost::shared_ptr<const M>&));
  void on_joint_states(const sensor_msgs::JointStateConstPtr& msg);
  void on_joint_accelerations(const mb_kinematics_msgs::JointAccelerationsConstPtr& msg);
  void on_odometry(const nav_msgs::OdometryConstPtr& msg);
  // ~reload: the model source read again; on success everything that depends on the model
  // (input, estimators, pairing, outputs, latched topics) is made anew.
  bool on_reload(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  // Makes everything that depends on the model (and the segments of the body it lacks).
  void start(const mbk::Model& loaded, const std::vector<std::string>& missing_segments);
  void make_outputs_in_r();  // the outputs, once R is known
  OutputSetup setup();
  void process(const std::vector<NodeInput::Ready>& ready);
  void process(const NodeInput::Ready& ready);  // one sample: merge, compute, publish
  // The samples waiting for odometry that are due at `now` (NodeInput::release), in order.
  void release_waiting(NodeInput::Clock::time_point now);
  // Computes and publishes the sample filled (or released) up to `level`.
  void emit(const ros::Time& stamp, mbk::Level level, mbk::Level wanted,
            NodeInput::Clock::time_point start);
  mbk::Level wanted_level();  // asks each output once whether it is listened to
  bool compute(mbk::Level level);
  void publish(const ros::Time& stamp, const Sample& sample, bool uses_data);

  NodeParams params_;
  ros::NodeHandle nh_, pnh_;
  NodeInput input_;
  mbk::Data<double> data_;                     // of input_.model()
  std::vector<std::string> missing_segments_;  // of the loaded model's body (load_node_model)
  Outputs outputs_;
  std::vector<char> active_;      // per output: listened to for the current sample
  PublishRate rate_;              // ~publish_frequency
  ImmediateCallbackQueue queue_;  // the input's callbacks; the others lock its mutex
  ros::Subscriber joint_states_sub_, accelerations_sub_, odometry_sub_;
  // Some joint_accelerations publisher is there: kept by a timer on the handle's queue (and set
  // by each joint_accelerations message), so that no input callback asks roscpp (its topic
  // manager's lock, taken in the other order by a nodelet loading beside it: a deadlock).
  std::atomic<bool> pairing_{false};
  ros::WallTimer pairing_timer_;
  ros::SteadyTimer wait_timer_;  // ~base_odometry_wait: releases the samples whose wait ended
  ros::ServiceServer reload_service_;
};

}  // namespace mbk_ros
