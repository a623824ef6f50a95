// mb_kinematics_node: see kinematics_node.h and the parameter table of doc/node.md.
#include <ros/ros.h>

#include <exception>
#include <memory>

#include "mb_kinematics/ros/kinematics_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mb_kinematics_node");
  ros::NodeHandle nh, pnh("~");  // kept alive: the last handle's end shuts ROS (and logging) down
  std::unique_ptr<mbk_ros::KinematicsNode> node;
  try {
    node = std::make_unique<mbk_ros::KinematicsNode>(nh, pnh);
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("mb_kinematics_node: " << e.what());
    return 1;
  }
  ros::spin();
  return 0;
}
