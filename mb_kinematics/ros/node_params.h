// Every parameter of mb_kinematics_node, read in one place (read_node_params), and the model
// they name (load_node_model). The parameter table of doc/node.md lists the same names and
// defaults.
#pragma once

#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/load_model.h"

namespace mbk_ros {

// ~missing_coordinates: what the node does about coordinates that never arrived (doc/node.md).
enum class MissingCoordinates {
  kSkip,  // publish the bodies whose chain of coordinates is known; leave the others out
  kWait,  // publish nothing until every coordinate has come once
  kZero,  // take them as 0 (Euler parameters: the identity), with a warning naming them
};

struct NodeParams {
  std::string robot_description;  // robot_description (URDF text), if set
  std::string model;              // ~model: a .urdf, .yaml or .bvh path; wins over it
  mbk::BvhModelOptions bvh;       // ~scale, ~body_mass (kg), ~sex, ~anthropometry: a .bvh ~model's
  std::vector<int> lower_body_array;    // ~lower_body_array: a bare scene; wins over both
  std::string joint_type = "ball_123";  // ~joint_type: the bare scene's joints
  std::string frame_id;                 // ~frame_id: R's frame; "" = URDF root link / scene frame
  std::string frame_prefix;             // ~frame_prefix: before every frame taken from the model
  bool per_body_topics = false;         // ~per_body_topics: body/<name>/twist and .../accel
  std::vector<std::string> per_body_names;  // ~per_body_topics as a list: those bodies only
  bool publish_markers = false;  // ~publish_markers: body_kinematics/markers (MarkerArray)
  bool tf = true, body_kinematics = true, twist = true, accel = true;  // ~outputs
  // ~acceleration_estimator: the best zero-latency tradeoff of the work-precision report
  std::string acceleration_estimator = "kalman_smooth";
  double max_sample_gap = 1.0;   // ~max_sample_gap (s): no derivative across a longer pause
  double publish_frequency = 0;  // ~publish_frequency (Hz): outputs at most this often; 0: all
  int queue_size = 50;           // ~queue_size: of the joint_states and joint_accelerations queues
  std::string base_odometry;     // ~base_odometry: nav_msgs/Odometry of the base; "" = off
  double base_odometry_max_gap = 0.2;  // ~base_odometry_max_gap (s): odometry held this long
  // ~base_odometry_wait (s): how long a joint sample waits for the odometry after its stamp
  double base_odometry_wait = 0.1;
  bool base_odometry_extrapolate = false;  // ~base_odometry_extrapolate: else the odometry held
  bool publish_base_tf = false;            // ~publish_base_tf: R -> base on /tf too
  MissingCoordinates missing_coordinates = MissingCoordinates::kSkip;  // ~missing_coordinates
  // ~partial_velocities_max_entries: a ~get_partial_velocities request needing more columns
  // (entries: a speed's 4 vectors, about 100 bytes) is refused (doc/node.md).
  int partial_velocities_max_entries = 100000;
};

// Reads the parameters; throws std::invalid_argument naming a bad one.
NodeParams read_node_params(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

// Reads the model source again into `p` (robot_description, ~model, ~lower_body_array,
// ~joint_type), for ~reload; throws like read_node_params.
void read_model_source(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, NodeParams& p);

// The model the parameters name: ~lower_body_array, else ~model, else robot_description (URDF),
// each source read once, with the segments of the body the model lacks (mbk::ModelFile's: a .bvh
// ~model's, with ~body_mass; empty for any other source). Euler-parameter joints get
// coordinate-derivative speeds. Throws std::invalid_argument.
mbk::ModelFile load_node_model(const NodeParams& params);

}  // namespace mbk_ros
