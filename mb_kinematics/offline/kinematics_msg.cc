#include "mb_kinematics/offline/kinematics_msg.h"

#include <Eigen/Geometry>

#include "mb_kinematics/core/joint_motion.h"

namespace mbk_offline {
namespace {

template <typename T>
void set_vector(const mbk::Vec3<double>& v, T& out) {
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
}

template <typename T>
void set_quaternion(const mbk::Mat3<double>& r, T& out) {
  const Eigen::Quaterniond q(r);
  out.x = q.x();
  out.y = q.y();
  out.z = q.z();
  out.w = q.w();
}

}  // namespace

void init_kinematics_msg(const mbk::Model& model, const std::string& frame,
                         mb_kinematics_msgs::BodyKinematicsArray& msg) {
  msg.header.frame_id = frame;
  msg.bodies.resize(model.body_count());
  for (int k = 1; k <= model.body_count(); ++k) {
    auto& b = msg.bodies[k - 1];
    b.name = model.bodies[k].name;
    b.index = k;
    b.lower_body = model.bodies[k].lower;
  }
}

void fill_kinematics_msg(const mbk::Model& model, const mbk::Data<double>& data,
                         mb_kinematics_msgs::BodyKinematicsArray& msg) {
  for (int k = 1; k <= model.body_count(); ++k) {
    auto& b = msg.bodies[k - 1];
    set_vector(data.origin[k], b.pose.position);
    set_quaternion(data.rotation[k], b.pose.orientation);
    set_vector(data.mass_center[k], b.mass_center);
    set_vector(data.omega[k], b.twist.angular);
    set_vector(data.mass_center_velocity[k], b.twist.linear);
    set_vector(data.alpha[k], b.accel.angular);
    set_vector(data.mass_center_acceleration[k], b.accel.linear);
  }
}

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
