#include "mb_kinematics/ros/node_params.h"

#include <cmath>
#include <stdexcept>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"

namespace mbk_ros {
namespace {

// Like getParam, but a parameter that is set with the wrong type is an error, not a default.
template <typename T>
void get(const ros::NodeHandle& nh, const std::string& name, T& value, const char* type) {
  if (nh.hasParam(name) && !nh.getParam(name, value))
    throw std::invalid_argument(nh.resolveName(name) + " must be " + type);
}

MissingCoordinates missing_coordinates(const ros::NodeHandle& pnh) {
  std::string mode = "skip";
  get(pnh, "missing_coordinates", mode, "a string: skip, wait or zero");
  if (mode == "skip") return MissingCoordinates::kSkip;
  if (mode == "wait") return MissingCoordinates::kWait;
  if (mode == "zero") return MissingCoordinates::kZero;
  throw std::invalid_argument(pnh.resolveName("missing_coordinates") + ": unknown value '" + mode +
                              "' (allowed: skip, wait, zero)");
}

}  // namespace

NodeParams read_node_params(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  NodeParams p;
  read_model_source(nh, pnh, p);
  get(pnh, "frame_id", p.frame_id, "a string");
  get(pnh, "frame_prefix", p.frame_prefix, "a string");
  if (!pnh.getParam("per_body_topics", p.per_body_names))  // a list of bodies, or a bool
    get(pnh, "per_body_topics", p.per_body_topics, "true, false or a list of body names");
  else
    p.per_body_topics = true;
  get(pnh, "publish_markers", p.publish_markers, "true or false");
  get(pnh, "acceleration_estimator", p.acceleration_estimator, "a string");
  get(pnh, "max_sample_gap", p.max_sample_gap, "a number of seconds");
  if (!(p.max_sample_gap >= 0))
    throw std::invalid_argument(pnh.resolveName("max_sample_gap") + " must be >= 0");
  get(pnh, "publish_frequency", p.publish_frequency, "a number of Hz");
  if (!(p.publish_frequency >= 0 && std::isfinite(p.publish_frequency)))
    throw std::invalid_argument(pnh.resolveName("publish_frequency") +
                                " must be >= 0 (Hz; 0: every sample)");
  get(pnh, "queue_size", p.queue_size, "an integer");
  if (p.queue_size < 1)
    throw std::invalid_argument(pnh.resolveName("queue_size") + " must be >= 1");
  get(pnh, "base_odometry", p.base_odometry, "a string (topic name)");
  get(pnh, "base_odometry_max_gap", p.base_odometry_max_gap, "a number of seconds");
  if (!(p.base_odometry_max_gap > 0 && std::isfinite(p.base_odometry_max_gap)))
    throw std::invalid_argument(pnh.resolveName("base_odometry_max_gap") + " must be > 0 (s)");
  get(pnh, "base_odometry_wait", p.base_odometry_wait, "a number of seconds");
  if (!(p.base_odometry_wait >= 0 && p.base_odometry_wait <= 10))
    throw std::invalid_argument(pnh.resolveName("base_odometry_wait") +
                                " must be in [0, 10] (s; 0: no wait)");
  get(pnh, "base_odometry_extrapolate", p.base_odometry_extrapolate, "true or false");
  get(pnh, "publish_base_tf", p.publish_base_tf, "true or false");
  p.missing_coordinates = missing_coordinates(pnh);
  get(pnh, "partial_velocities_max_entries", p.partial_velocities_max_entries, "an integer");
  if (p.partial_velocities_max_entries < 0)
    throw std::invalid_argument(pnh.resolveName("partial_velocities_max_entries") +
                                " must be >= 0");
  std::vector<std::string> outputs;
  get(pnh, "outputs", outputs, "a list of strings, e.g. [tf, body_kinematics]");
  if (pnh.hasParam("outputs")) {
    p.tf = p.body_kinematics = p.twist = p.accel = false;
    for (const std::string& o : outputs) {
      if (o == "tf")
        p.tf = true;
      else if (o == "body_kinematics")
        p.body_kinematics = true;
      else if (o == "twist")
        p.twist = true;
      else if (o == "accel")
        p.accel = true;
      else
        throw std::invalid_argument("~outputs: unknown output '" + o +
                                    "' (known: tf, body_kinematics, twist, accel)");
    }
  }
  return p;
}

void read_model_source(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, NodeParams& p) {
  const NodeParams defaults;  // a source no longer set falls back to its default
  p.robot_description = defaults.robot_description;
  p.model = defaults.model;
  p.lower_body_array = defaults.lower_body_array;
  p.joint_type = defaults.joint_type;
  p.bvh = defaults.bvh;
  get(nh, "robot_description", p.robot_description, "a string (URDF)");
  get(pnh, "model", p.model, "a string (path)");
  get(pnh, "scale", p.bvh.scale, "a number (metres per unit of a .bvh ~model)");
  get(pnh, "body_mass", p.bvh.body_mass, "a number (kg)");
  get(pnh, "sex", p.bvh.sex, "a string: male or female");
  get(pnh, "anthropometry", p.bvh.anthropometry, "a string: de_leva or dempster");
  get(pnh, "lower_body_array", p.lower_body_array, "a list of integers");
  get(pnh, "joint_type", p.joint_type, "a string");
}

mbk::ModelFile load_node_model(const NodeParams& p) {
  mbk::ModelFile loaded;
  mbk::Model& model = loaded.model;
  if (!p.lower_body_array.empty()) {
    model = mbk::make_bare_model(p.lower_body_array, mbk::joint_type_from_string(p.joint_type));
  } else if (!p.model.empty()) {
    loaded = mbk::read_model_file(p.model, p.bvh);
  } else if (!p.robot_description.empty()) {
    model = mbk::load_xml_string(p.robot_description, "robot_description");
  } else {
    throw std::invalid_argument(
        "no model: set the robot_description parameter (URDF), ~model (a .urdf, .xml, .sdf, .yaml or "
        ".bvh path) or ~lower_body_array");
  }
  if (model.speeds != mbk::SpeedKind::kCoordinateDerivatives) {  // the node's speeds: q'
    model.speeds = mbk::SpeedKind::kCoordinateDerivatives;
    mbk::finalize_model(model);
  }
  return loaded;
}

}  // namespace mbk_ros
