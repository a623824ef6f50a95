// body_kinematics/markers (~publish_markers): the rviz display's picture of body_kinematics as
// a visualization_msgs/MarkerArray (kinematics_markers.h), each quantity auto-scaled as the
// display's default (mb_kinematics/viz/auto_lengths.h): its longest arrow 0.4 of the robot's
// size.
#pragma once

#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <ros/publisher.h>

#include <vector>

#include "mb_kinematics/ros/kinematics_markers.h"
#include "mb_kinematics/ros/outputs/output.h"
#include "mb_kinematics/viz/auto_lengths.h"

namespace mbk_ros {

class MarkersOutput : public Output {
 public:
  static bool enabled(const NodeParams& p) { return p.publish_markers; }
  explicit MarkersOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kAcceleration; }
  bool active() override { return publisher_.getNumSubscribers() > 0; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  ros::Publisher publisher_;
  mb_kinematics_msgs::BodyKinematicsArray kinematics_;  // what the picture shows
  std::vector<char> shown_;  // per body: in kinematics_ (~missing_coordinates skip)
  GlyphStyle style_;
  mbk::AutoLengths lengths_;
};

}  // namespace mbk_ros
