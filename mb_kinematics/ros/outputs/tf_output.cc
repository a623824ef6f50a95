#include "mb_kinematics/ros/outputs/tf_output.h"

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/ros/outputs/message_fields.h"

namespace mbk_ros {
namespace {

// The joint's relative transform: q_k + s_k in Bj, and SJK.
void set_transform(const mbk::Body& body, const mbk::JointMotion<double>& m,
                   geometry_msgs::Transform& out) {
  set_vector(body.joint.offset + m.translation, out.translation);
  set_quaternion(m.rotation, out.rotation);
}

}  // namespace

TfOutput::TfOutput(const OutputSetup& setup) {
  const mbk::Model& model = setup.model;
  for (int k = 1; k <= model.body_count(); ++k)
    if (mbk::coordinate_count(model.bodies[k].joint.type) > 0) moving_.push_back(k);
  transforms_.resize(moving_.size());
  last_stamp_.resize(moving_.size());
  out_.reserve(moving_.size());
  for (size_t i = 0; i < moving_.size(); ++i) {
    transforms_[i].header.frame_id = setup.lower_frame(moving_[i]);
    transforms_[i].child_frame_id = setup.body_frame(moving_[i]);
  }
}

void TfOutput::publish(const ros::Time& stamp, const Sample& sample) {
  mbk::JointMotion<double> m;
  out_.clear();
  for (size_t i = 0; i < moving_.size(); ++i) {
    if (last_stamp_[i] == stamp) continue;        // tf2 rejects repeated stamps
    if (!sample.published[moving_[i]]) continue;  // ~missing_coordinates skip
    const mbk::Body& body = sample.model.bodies[moving_[i]];
    mbk::joint_motion<double>(body.joint, sample.model.speeds,
                              sample.state.position.data() + body.q_index, nullptr, m);
    transforms_[i].header.stamp = stamp;
    set_transform(body, m, transforms_[i].transform);
    last_stamp_[i] = stamp;
    out_.push_back(transforms_[i]);
  }
  if (!out_.empty()) broadcaster_.sendTransform(out_);
}

TfStaticOutput::TfStaticOutput(const OutputSetup& setup) {
  const mbk::Model& model = setup.model;
  std::vector<geometry_msgs::TransformStamped> fixed;
  mbk::JointMotion<double> m;
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& body = model.bodies[k];
    if (mbk::coordinate_count(body.joint.type) > 0) continue;
    mbk::joint_motion<double>(body.joint, model.speeds, nullptr, nullptr, m);
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = setup.lower_frame(k);
    t.child_frame_id = setup.body_frame(k);
    set_transform(body, m, t.transform);
    fixed.push_back(t);
  }
  if (!fixed.empty()) broadcaster_.sendTransform(fixed);
}

}  // namespace mbk_ros
