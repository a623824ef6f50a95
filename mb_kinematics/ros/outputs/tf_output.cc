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

TfOutput::TfOutput(const OutputSetup& setup)
    : publisher_(setup.nh.advertise<tf2_msgs::TFMessage>("/tf", 100)) {
  const mbk::Model& model = setup.model;
  // With ~base_odometry, body 1 is the base: R -> base comes from the odometry's source.
  const bool base_tf = setup.params.base_odometry.empty() || setup.params.publish_base_tf;
  for (int k = base_tf ? 1 : 2; k <= model.body_count(); ++k)
    if (mbk::coordinate_count(model.bodies[k].joint.type) > 0) moving_.push_back(k);
  std::vector<geometry_msgs::TransformStamped>& transforms = msg_.next().transforms;
  transforms.resize(moving_.size());
  for (size_t i = 0; i < moving_.size(); ++i) {
    transforms[i].header.frame_id = setup.lower_frame(moving_[i]);
    transforms[i].child_frame_id = setup.body_frame(moving_[i]);
  }
}

void fill_transforms(const mbk::Model& model, const mbk::JointState<double>& state,
                     const std::vector<int>& moving, const ros::Time& stamp,
                     std::vector<geometry_msgs::TransformStamped>& transforms) {
  mbk::JointMotion<double> m;
  for (size_t i = 0; i < moving.size(); ++i) {
    const mbk::Body& body = model.bodies[moving[i]];
    mbk::joint_motion<double>(body.joint, model.speeds, state.position.data() + body.q_index,
                              nullptr, m);
    transforms[i].header.stamp = stamp;
    set_transform(body, m, transforms[i].transform);
  }
}

void TfOutput::publish(const ros::Time& stamp, const Sample& sample) {
  if (moving_.empty() || stamp == last_stamp_) return;  // tf2 rejects repeated stamps
  last_stamp_ = stamp;
  fill_transforms(sample.model, sample.state, moving_, stamp, msg_.next().transforms);
  msg_.publish(publisher_);
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
