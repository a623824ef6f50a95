#include "mb_kinematics/ros/node_params.h"

#include <stdexcept>

namespace mbk_ros {
namespace {

// Like getParam, but a parameter that is set with the wrong type is an error, not a default.
template <typename T>
void get(const ros::NodeHandle& nh, const std::string& name, T& value, const char* type) {
  if (nh.hasParam(name) && !nh.getParam(name, value))
    throw std::invalid_argument(nh.resolveName(name) + " must be " + type);
}

}  // namespace

NodeParams read_node_params(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  NodeParams p;
  get(nh, "robot_description", p.robot_description, "a string (URDF)");
  get(pnh, "model", p.model, "a string (path)");
  get(pnh, "lower_body_array", p.lower_body_array, "a list of integers");
  get(pnh, "joint_type", p.joint_type, "a string");
  get(pnh, "frame_id", p.frame_id, "a string");
  get(pnh, "per_body_topics", p.per_body_topics, "true or false");
  get(pnh, "publish_markers", p.publish_markers, "true or false");
  get(pnh, "acceleration_estimator", p.acceleration_estimator, "a string");
  get(pnh, "max_sample_gap", p.max_sample_gap, "a number of seconds");
  if (!(p.max_sample_gap >= 0))
    throw std::invalid_argument(pnh.resolveName("max_sample_gap") + " must be >= 0");
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

}  // namespace mbk_ros
