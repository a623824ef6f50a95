#include "mb_kinematics/ros/outputs/body_motion_output.h"

#include <geometry_msgs/AccelStamped.h>
#include <geometry_msgs/TwistStamped.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "mb_kinematics/core/body_velocity.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_ros {
using mbk_messages::set_vector;

std::string body_topic_name(const std::string& body) {
  std::string out = body;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out[0]))) out = "b_" + out;
  return out;
}

BodyMotionOutput::BodyMotionOutput(const OutputSetup& setup, Kind kind)
    : kind_(kind),
      publishers_(setup.model.body_count() + 1),
      frames_(setup.model.body_count() + 1),
      listened_(setup.model.body_count() + 1, 0) {
  const std::vector<std::string>& only = setup.params.per_body_names;  // empty: every body
  for (const std::string& name : only)
    if (setup.model.body_index(name) < 1)
      throw std::invalid_argument("~per_body_topics: '" + name + "' is no body of the model");
  for (int k = 1; k <= setup.model.body_count(); ++k) {
    frames_[k] = setup.frames().body(k);
    if (!only.empty() &&
        std::find(only.begin(), only.end(), setup.model.bodies[k].name) == only.end())
      continue;
    const std::string base = "body/" + body_topic_name(setup.model.bodies[k].name);
    publishers_[k] =
        kind == Kind::kTwist
            ? setup.nh.advertise<geometry_msgs::TwistStamped>(base + "/twist", kSampleQueueSize)
            : setup.nh.advertise<geometry_msgs::AccelStamped>(base + "/accel", kSampleQueueSize);
  }
}

mbk::Level BodyMotionOutput::level() const {
  return kind_ == Kind::kTwist ? mbk::Level::kVelocity : mbk::Level::kAcceleration;
}

bool BodyMotionOutput::active() {
  bool any = false;
  for (size_t k = 1; k < publishers_.size(); ++k) {
    listened_[k] = publishers_[k] && publishers_[k].getNumSubscribers() > 0;
    any = any || listened_[k];
  }
  return any;
}

void BodyMotionOutput::publish(const ros::Time& stamp, const Sample& sample) {
  const mbk::Vec3<double> origin = mbk::Vec3<double>::Zero();  // of O_k, in Bk
  for (size_t k = 1; k < publishers_.size(); ++k) {
    if (!listened_[k] || !sample.published[k]) continue;  // ~missing_coordinates skip
    const std::string& frame = frames_[k];
    if (kind_ == Kind::kTwist) {
      const auto v = mbk::point_velocity(sample.data, k, origin, mbk::ReferenceFrame::kBody);
      geometry_msgs::TwistStamped t;
      t.header.stamp = stamp;
      t.header.frame_id = frame;
      set_vector(v.angular, t.twist.angular);
      set_vector(v.linear, t.twist.linear);
      publishers_[k].publish(t);
    } else {
      const auto a = mbk::point_acceleration(sample.data, k, origin, mbk::ReferenceFrame::kBody);
      geometry_msgs::AccelStamped msg;
      msg.header.stamp = stamp;
      msg.header.frame_id = frame;
      set_vector(a.angular, msg.accel.angular);
      set_vector(a.linear, msg.accel.linear);
      publishers_[k].publish(msg);
    }
  }
}

}  // namespace mbk_ros
