#include "mb_kinematics/messages/tf.h"

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_messages {

TfJoint tf_joint(const mbk::Model& model, int body) {
  const mbk::Joint& joint = model.bodies[body].joint;
  return {body, Eigen::Quaterniond(joint.rotation), mbk::translation_count(joint.type) > 0};
}

std::vector<int> moving_bodies(const mbk::Model& model, int first) {
  std::vector<int> out;
  for (int k = first; k <= model.body_count(); ++k)
    if (mbk::coordinate_count(model.bodies[k].joint.type) > 0) out.push_back(k);
  return out;
}

void init_transforms(const mbk::Model& model, const FrameNames& names,
                     const std::vector<int>& bodies, std::vector<TfJoint>& moving,
                     std::vector<geometry_msgs::TransformStamped>& transforms,
                     const std::string& base_frame) {
  moving.clear();
  transforms.resize(bodies.size() + (base_frame.empty() ? 0 : 1));
  for (size_t i = 0; i < bodies.size(); ++i) {
    moving.push_back(tf_joint(model, bodies[i]));
    transforms[i].header.frame_id = names.lower(bodies[i]);
    transforms[i].child_frame_id = names.body(bodies[i]);
  }
  if (base_frame.empty()) return;
  transforms.back().header.frame_id = base_frame;
  transforms.back().child_frame_id = names.root();
}

void fill_transforms(const mbk::Model& model, const mbk::JointState<double>& state,
                     const std::vector<TfJoint>& moving, const ros::Time& stamp,
                     std::vector<geometry_msgs::TransformStamped>& transforms,
                     const mbk::BaseMotion* base) {
  mbk::JointMotion<double> m;
  for (size_t i = 0; i < moving.size(); ++i) {
    const mbk::Body& body = model.bodies[moving[i].body];
    const double* q = state.position.data() + body.q_index;
    geometry_msgs::Transform& out = transforms[i].transform;
    transforms[i].header.stamp = stamp;
    set_quaternion(mbk::joint_quaternion(body.joint, moving[i].offset, q), out.rotation);
    if (!moving[i].translates) {
      set_vector(body.joint.offset, out.translation);
      continue;
    }
    mbk::joint_motion<double>(body.joint, model.speeds, q, nullptr, m);
    set_vector(body.joint.offset + m.translation, out.translation);  // q_k + s_k in Bj
  }
  if (transforms.size() == moving.size()) return;
  geometry_msgs::TransformStamped& root = transforms.back();  // the floating base
  root.header.stamp = stamp;
  if (!base) return;
  set_vector(base->position, root.transform.translation);
  set_quaternion(base->rotation, root.transform.rotation);
}

std::vector<geometry_msgs::TransformStamped> fixed_transforms(const mbk::Model& model,
                                                              const FrameNames& names,
                                                              const ros::Time& stamp) {
  std::vector<geometry_msgs::TransformStamped> out;
  mbk::JointMotion<double> m;
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& body = model.bodies[k];
    if (mbk::coordinate_count(body.joint.type) > 0) continue;
    mbk::joint_motion<double>(body.joint, model.speeds, nullptr, nullptr, m);
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = names.lower(k);
    t.child_frame_id = names.body(k);
    set_vector(body.joint.offset + m.translation, t.transform.translation);
    set_quaternion(m.rotation, t.transform.rotation);
    out.push_back(t);
  }
  return out;
}

}  // namespace mbk_messages
