#include "mb_kinematics/ros/outputs/tf_duplicate_watch.h"

#include <ros/console.h>
#include <ros/this_node.h>

#include "mb_kinematics/core/printable.h"

namespace mbk_ros {
namespace {

// One line: the other node, the frame, and what to do.
std::string duplicate_tf_warning(const std::string& node, const std::string& frame) {
  return "mb_kinematics: " + mbk::printable(node) + " also publishes frame '" +
         mbk::printable(frame) +
         "' on /tf, as this node does: tf listeners get it twice (TF_REPEATED_DATA); leave /tf "
         "to it with the launch argument publish_tf:=false (the node's ~outputs without tf)";
}

}  // namespace

// Its callbacks run on the node's handle queue, one at a time with ~reload, which ends the watch.
TfDuplicateWatch::TfDuplicateWatch(ros::NodeHandle& nh, const std::vector<std::string>& frames)
    : frames_(frames.begin(), frames.end()) {
  if (frames_.empty()) return;
  subscriber_ = nh.subscribe("/tf", 100, &TfDuplicateWatch::on_tf, this);
  listening_ = true;
  timer_ = nh.createWallTimer(
      ros::WallDuration(kWatchSeconds), [this](const ros::WallTimerEvent&) { stop(); }, true);
}

void TfDuplicateWatch::on_tf(const ros::MessageEvent<const tf2_msgs::TFMessage>& event) {
  if (!listening_ || event.getPublisherName() == ros::this_node::getName()) return;
  for (const geometry_msgs::TransformStamped& t : event.getMessage()->transforms) {
    if (!frames_.count(t.child_frame_id)) continue;
    ROS_WARN_STREAM(duplicate_tf_warning(event.getPublisherName(), t.child_frame_id));
    stop();
    return;
  }
}

void TfDuplicateWatch::stop() {
  listening_ = false;
  subscriber_.shutdown();
  timer_.stop();
}

}  // namespace mbk_ros
