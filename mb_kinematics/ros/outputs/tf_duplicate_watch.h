// Another node publishing this node's frames on /tf, as a robot_state_publisher of the same
// robot does: tf listeners then get every frame twice and warn TF_REPEATED_DATA (rviz thousands
// of times a minute). Watched for a while after the node starts or reloads: the first /tf
// message from another node that names one of this node's moving frames gives one warning
// naming that node and the launch argument that leaves /tf to it (doc/node.md).
#pragma once

#include <ros/message_event.h>
#include <ros/node_handle.h>
#include <ros/subscriber.h>
#include <ros/timer.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <string>
#include <unordered_set>
#include <vector>

namespace mbk_ros {

class TfDuplicateWatch {
 public:
  // How long after it is made it listens to /tf, unless it finds a duplicate before.
  static constexpr double kWatchSeconds = 60.0;

  // `frames`: the child frames this node publishes on /tf.
  TfDuplicateWatch(ros::NodeHandle& nh, const std::vector<std::string>& frames);
  // Whether its own subscription to /tf is up (the node's /tf publisher counts it).
  bool listening() const { return listening_; }

 private:
  void on_tf(const ros::MessageEvent<const tf2_msgs::TFMessage>& event);
  void stop();

  std::unordered_set<std::string> frames_;
  std::atomic<bool> listening_{false};
  ros::Subscriber subscriber_;
  ros::WallTimer timer_;
};

}  // namespace mbk_ros
