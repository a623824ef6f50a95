// /tf and /tf_static: a frame per body, parent = its lower body's frame (R for L(k) = 0), the
// relative transform q_k + s_k, SJK of its joint alone (messages/tf.h). Fixed joints never move:
// /tf_static, once at start (doc/method.md 8).
#pragma once

#include <ros/publisher.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/messages/tf.h"
#include "mb_kinematics/ros/outputs/output.h"
#include "mb_kinematics/ros/outputs/reused_serialization.h"
#include "mb_kinematics/ros/outputs/tf_duplicate_watch.h"

namespace mbk_ros {

// The joints with coordinates, every sample (with ~base_odometry, the base's only with
// ~publish_base_tf): one TFMessage, its frames set once (and again when ~missing_coordinates
// skip leaves bodies out or lets them join), published as tf2_ros::TransformBroadcaster does
// (/tf, queue 100) without its per-sample copy. Warns once if another node publishes these
// frames on /tf too (tf_duplicate_watch.h).
class TfOutput : public Output {
 public:
  static bool enabled(const NodeParams& p) { return p.tf; }
  explicit TfOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }
  // tf listeners other than the watch's own subscription
  bool active() override { return publisher_.getNumSubscribers() > (watch_->listening() ? 1u : 0u); }
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  void select(const mbk::Model& model, const std::vector<char>& published,
              tf2_msgs::TFMessage& msg);

  std::string prefix_, frame_;                    // ~frame_prefix, R
  std::vector<int> moving_all_;                   // bodies on joints with coordinates
  std::vector<mbk_messages::TfJoint> moving_;     // those of them published now
  std::vector<char> shown_;                       // per body: published now
  ReusedSerialization<tf2_msgs::TFMessage> msg_;  // a transform per body of moving_
  ros::Time last_stamp_;
  ros::Publisher publisher_;
  std::unique_ptr<TfDuplicateWatch> watch_;
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
