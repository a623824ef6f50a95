// body/<name>/twist and body/<name>/accel (~per_body_topics; ~outputs twist, accel):
// geometry_msgs/TwistStamped and AccelStamped of the origin O_k, in the body's own frame, so
// that rviz draws them at the body and rqt_plot shows them. One publisher per body; a body's
// message is filled only while it has a subscriber. ~per_body_topics as a list of body names:
// those bodies only.
#pragma once

#include <ros/publisher.h>

#include <string>
#include <vector>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

// A graph-name-safe version of a body name for per-body topics.
std::string body_topic_name(const std::string& body);

class BodyMotionOutput : public Output {
 public:
  enum class Kind { kTwist, kAccel };
  BodyMotionOutput(const OutputSetup& setup, Kind kind);
  mbk::Level level() const override;
  bool active() override;  // notes which bodies have subscribers
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  Kind kind_;
  std::vector<ros::Publisher> publishers_;  // index k; [0] unused
  std::vector<std::string> frames_;         // index k: Bk's tf frame
  std::vector<char> listened_;              // index k: a subscriber at the last active()
};

struct BodyTwistOutput : BodyMotionOutput {
  static bool enabled(const NodeParams& p) { return p.per_body_topics && p.twist; }
  explicit BodyTwistOutput(const OutputSetup& setup) : BodyMotionOutput(setup, Kind::kTwist) {}
};

struct BodyAccelOutput : BodyMotionOutput {
  static bool enabled(const NodeParams& p) { return p.per_body_topics && p.accel; }
  explicit BodyAccelOutput(const OutputSetup& setup) : BodyMotionOutput(setup, Kind::kAccel) {}
};

}  // namespace mbk_ros
