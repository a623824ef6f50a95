// mb_kinematics/KinematicsNodelet: mb_kinematics_node as a nodelet (nodelet_plugins.xml), the
// same KinematicsNode on the nodelet's handles, for consumers in the same process: they get
// body_kinematics and /tf by shared pointer, without serialization (doc/node.md).
#include <nodelet/nodelet.h>

#include <exception>
#include <memory>
#include <pluginlib/class_list_macros.hpp>

#include "mb_kinematics/ros/kinematics_node.h"

namespace mbk_ros {

class KinematicsNodelet : public nodelet::Nodelet {
 private:
  // The input's callbacks run as messages arrive (immediate_callback_queue.h), the others on the
  // manager's single-threaded queue (getNodeHandle()); all of them one at a time.
  void onInit() override {
    try {
      node_ = std::make_unique<KinematicsNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL_STREAM("mb_kinematics nodelet: " << e.what());
      throw nodelet::Exception(e.what());
    }
  }

  std::unique_ptr<KinematicsNode> node_;
};

}  // namespace mbk_ros

PLUGINLIB_EXPORT_CLASS(mbk_ros::KinematicsNodelet, nodelet::Nodelet)
