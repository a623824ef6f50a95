// body_kinematics (mb_kinematics_msgs/BodyKinematicsArray): every body's pose, mass center,
// twist (omega_k, velocity of G_k) and accel (alpha_k, acceleration of G_k), all in R; and
// lower_body_array (latched mb_kinematics_msgs/LowerBodyArray), the topology, once.
#pragma once

#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <ros/publisher.h>

#include <vector>

#include "mb_kinematics/messages/body_kinematics.h"
#include "mb_kinematics/ros/outputs/output.h"
#include "mb_kinematics/ros/outputs/reused_serialization.h"

namespace mbk_ros {

class BodyKinematicsOutput : public Output {
 public:
  static bool enabled(const NodeParams& p) { return p.body_kinematics; }
  explicit BodyKinematicsOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kAcceleration; }
  bool active() override { return publisher_.getNumSubscribers() > 0; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  ros::Publisher publisher_;
  ReusedSerialization<mb_kinematics_msgs::BodyKinematicsArray> msg_;
  std::vector<char> shown_;  // per body: in the message (~missing_coordinates skip)
};

class LowerBodyArrayOutput : public Output {
 public:
  static bool enabled(const NodeParams&) { return true; }
  explicit LowerBodyArrayOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }
  bool active() override { return false; }  // latched: nothing per sample
  void publish(const ros::Time&, const Sample&) override {}

 private:
  ros::Publisher publisher_;
};

}  // namespace mbk_ros
