// mb_kinematics_node: a thin adapter from joint_states to the core (doc/method.md 8; README "The
// node"), in the manner of robot_state_publisher: parameters read in one place, one callback
// per sample, throttled warnings that say what was wrong. It keeps the input (with the pairing
// with joint_accelerations: JointStateInput) and the dispatch to its outputs
// (outputs/output_table.cc); the outputs publish.
#pragma once

#include <mb_kinematics_msgs/JointAccelerations.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/ros/base_odometry_input.h"
#include "mb_kinematics/ros/coordinate_coverage.h"
#include "mb_kinematics/ros/input_problem.h"
#include "mb_kinematics/ros/joint_state_input.h"
#include "mb_kinematics/ros/node_params.h"
#include "mb_kinematics/ros/outputs/diagnostics_output.h"
#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

class KinematicsNode {
 public:
  // Reads the parameters, loads the model, logs the lower body arrays table, advertises and
  // subscribes. Throws std::invalid_argument (with a one-line reason) when it cannot start.
  KinematicsNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  void on_joint_states(const sensor_msgs::JointStateConstPtr& msg);
  void on_joint_accelerations(const mb_kinematics_msgs::JointAccelerationsConstPtr& msg);
  void on_odometry(const nav_msgs::OdometryConstPtr& msg);
  // ~reload: the model source read again; on success everything that depends on the model
  // (input, estimators, pairing, outputs, latched topics) is made anew.
  bool on_reload(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  void start(const mbk::Model& loaded);        // makes everything that depends on the model
  void make_outputs_in_r();                    // the outputs, once R is known
  bool add_base(double t, mbk::Level& level);  // ~base_odometry: state_ from input_state_
  void process(const std::vector<JointStateInput::Ready>& ready);
  void process(const sensor_msgs::JointState& msg);  // one sample: merge, compute, publish
  bool report(const JointStateInput::Update& update);
  bool cover(double t);  // ~missing_coordinates
  const std::vector<char>& published();
  void warn(InputProblem problem, const std::string& message);
  mbk::Level wanted_level();  // asks each output once whether it is listened to
  bool decimated(double t);
  bool compute(mbk::Level level);
  void publish(const ros::Time& stamp, const Sample& sample, bool uses_data);

  NodeParams params_;
  mbk::Model loaded_;       // as the model source gives it
  mbk::Model input_model_;  // the joints of joint_states
  mbk::Model model_;        // the kinematics: input_model_, with ~base_odometry after a base
  std::optional<JointStateInput> input_;
  std::optional<CoordinateCoverage> coverage_;  // over input_model_
  std::vector<char> published_;  // per body of model_ (with ~base_odometry: the base, then
                                 // coverage_'s bodies)
  mbk::JointState<double> input_state_, state_;  // input_state_: with ~base_odometry only
  mbk::Data<double> data_;
  std::unique_ptr<BaseOdometryInput> base_;  // with ~base_odometry
  std::string frame_;                        // R; with ~base_odometry "" until its first message

  ros::NodeHandle nh_, pnh_;
  std::vector<std::unique_ptr<Output>> outputs_;
  std::vector<std::unique_ptr<Output>> retired_;  // during start(): subscribers stay connected
  std::vector<char> active_;                      // per output: listened to for the current sample
  DiagnosticsOutput* diagnostics_;                // one of outputs_
  double last_output_ = -1e300;  // stamp of the last sample computed (~publish_frequency)
  ros::Subscriber joint_states_sub_, accelerations_sub_, odometry_sub_;
  ros::ServiceServer reload_service_;
  std::array<std::chrono::steady_clock::time_point, static_cast<size_t>(InputProblem::kCount)>
      last_warned_{};  // per class, for throttling
};

}  // namespace mbk_ros
