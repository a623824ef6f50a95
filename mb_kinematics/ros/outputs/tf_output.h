// /tf and /tf_static: a frame per body, parent = its lower body's frame (R for L(k) = 0), the
// relative transform q_k + s_k, SJK of its joint alone. Fixed joints never move: /tf_static,
// once at start (doc/method.md 8).
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <vector>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

// The joints with coordinates, every sample (with ~base_odometry, the base's only with
// ~publish_base_tf).
class TfOutput : public Output {
 public:
  static bool enabled(const NodeParams& p) { return p.tf; }
  explicit TfOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }
  bool active() override { return true; }  // tf listeners are not counted: always
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  std::vector<int> moving_;                                  // bodies on joints with coordinates
  std::vector<geometry_msgs::TransformStamped> transforms_;  // one per moving body
  std::vector<ros::Time> last_stamp_;                        // per moving body
  std::vector<geometry_msgs::TransformStamped> out_;
  tf2_ros::TransformBroadcaster broadcaster_;
};

// The fixed joints, once, when made.
class TfStaticOutput : public Output {
 public:
  static bool enabled(const NodeParams& p) { return p.tf; }
  explicit TfStaticOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }
  bool active() override { return false; }  // latched: nothing per sample
  void publish(const ros::Time&, const Sample&) override {}

 private:
  tf2_ros::StaticTransformBroadcaster broadcaster_;
};

}  // namespace mbk_ros
