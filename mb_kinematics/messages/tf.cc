#include "mb_kinematics/messages/tf.h"

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_offline {
using mbk_ros::set_quaternion;
using mbk_ros::set_vector;

TfFrames::TfFrames(const mbk::Model& model, const std::string& prefix)
    : model_(model), prefix_(prefix), root_(prefix + model.frame) {
  for (int k = 1; k <= model.body_count(); ++k)
    if (mbk::coordinate_count(model.bodies[k].joint.type) > 0) moving_.push_back(k);
  transforms_.resize(moving_.size());
  for (size_t i = 0; i < moving_.size(); ++i) {
    const mbk::Body& body = model.bodies[moving_[i]];
    transforms_[i].header.frame_id = body.lower ? prefix + model.bodies[body.lower].name : root_;
    transforms_[i].child_frame_id = prefix + body.name;
  }
}

// q_k + s_k in Bj and SJK, from the joint's own coordinates (as the node's /tf).
const std::vector<geometry_msgs::TransformStamped>& TfFrames::moving(
    const mbk::JointState<double>& state) {
  mbk::JointMotion<double> m;
  for (size_t i = 0; i < moving_.size(); ++i) {
    const mbk::Body& body = model_.bodies[moving_[i]];
    mbk::joint_motion<double>(body.joint, model_.speeds, state.position.data() + body.q_index,
                              nullptr, m);
    set_vector(body.joint.offset + m.translation, transforms_[i].transform.translation);
    set_quaternion(m.rotation, transforms_[i].transform.rotation);
  }
  return transforms_;
}

std::vector<geometry_msgs::TransformStamped> TfFrames::fixed() const {
  std::vector<geometry_msgs::TransformStamped> out;
  mbk::JointMotion<double> m;
  for (int k = 1; k <= model_.body_count(); ++k) {
    const mbk::Body& body = model_.bodies[k];
    if (mbk::coordinate_count(body.joint.type) > 0) continue;
    mbk::joint_motion<double>(body.joint, model_.speeds, nullptr, nullptr, m);
    geometry_msgs::TransformStamped t;
    t.header.frame_id = body.lower ? prefix_ + model_.bodies[body.lower].name : root_;
    t.child_frame_id = prefix_ + body.name;
    set_vector(body.joint.offset + m.translation, t.transform.translation);
    set_quaternion(m.rotation, t.transform.rotation);
    out.push_back(t);
  }
  return out;
}

}  // namespace mbk_offline
