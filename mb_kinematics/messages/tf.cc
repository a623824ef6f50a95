#include "mb_kinematics/messages/tf.h"

#include <algorithm>

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/sincos.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_messages {
namespace {

// The plain turns' half angles go through mbk::sin_cos over an array (a loop that vectorizes,
// bit for bit the one-angle sin_cos of mbk::joint_quaternion) this many at a time.
constexpr size_t kTurnBlock = 32;

// mbk::sin_cos over an array; on a CPU with AVX2 its loop on 256-bit vectors (flatten: inlined
// here, so compiled for AVX2; without fused multiply-adds: bit for bit the same).
#if defined(__x86_64__)
__attribute__((target("avx2"), flatten)) void half_angles_avx2(const double* x, int n, double* s,
                                                               double* c) {
  mbk::sin_cos(x, n, s, c);
}
#endif

void half_angles(const double* x, int n, double* s, double* c) {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return half_angles_avx2(x, n, s, c);
#endif
  mbk::sin_cos(x, n, s, c);
}

// The rotation and the stamp of moving[first, end) into `transforms`: the plain turns from their
// half angles' sines and cosines taken together, the others by mbk::joint_quaternion.
void fill_rotations(const mbk::Model& model, const mbk::JointState<double>& state,
                    const std::vector<TfJoint>& moving, size_t first, size_t end,
                    const ros::Time& stamp,
                    std::vector<geometry_msgs::TransformStamped>& transforms) {
  double half[kTurnBlock], s[kTurnBlock], c[kTurnBlock];
  const double* q = state.position.data();
  const TfJoint* joint = moving.data() + first;
  const size_t n = end - first;
  for (size_t i = 0; i < n; ++i) half[i] = joint[i].plain_turn ? q[joint[i].q_index] / 2 : 0.0;
  half_angles(half, static_cast<int>(n), s, c);
  geometry_msgs::TransformStamped* out = transforms.data() + first;
  for (size_t i = 0; i < n; ++i) {
    out[i].header.stamp = stamp;
    geometry_msgs::Quaternion& rotation = out[i].transform.rotation;
    if (!joint[i].plain_turn) {
      set_quaternion(mbk::joint_quaternion(model.bodies[joint[i].body].joint, joint[i].offset,
                                           q + joint[i].q_index),
                     rotation);
      continue;
    }
    const double si = s[i];  // joint_quaternion's values (a zero's sign aside)
    rotation.w = c[i];
    rotation.x = si * joint[i].axis.x();
    rotation.y = si * joint[i].axis.y();
    rotation.z = si * joint[i].axis.z();
  }
}

}  // namespace

TfJoint tf_joint(const mbk::Model& model, int body) {
  const mbk::Joint& joint = model.bodies[body].joint;
  const bool plain_turn =
      joint.type == mbk::JointType::kRevolute && joint.rotation == mbk::Mat3<double>::Identity();
  return {body,       Eigen::Quaterniond(joint.rotation), mbk::translation_count(joint.type) > 0,
          plain_turn, model.bodies[body].q_index,         joint.axis};
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
    if (!moving.back().translates)  // q_k alone: fill_transforms leaves it
      set_vector(model.bodies[bodies[i]].joint.offset, transforms[i].transform.translation);
  }
  if (base_frame.empty()) return;
  transforms.back().header.frame_id = base_frame;
  transforms.back().child_frame_id = names.root();
}

void fill_transforms(const mbk::Model& model, const mbk::JointState<double>& state,
                     const std::vector<TfJoint>& moving, const ros::Time& stamp,
                     std::vector<geometry_msgs::TransformStamped>& transforms,
                     const mbk::BaseMotion* base) {
  for (size_t first = 0; first < moving.size(); first += kTurnBlock)
    fill_rotations(model, state, moving, first, std::min(moving.size(), first + kTurnBlock), stamp,
                   transforms);
  mbk::JointMotion<double> m;
  const size_t n = moving.size();  // not read again after each joint_motion call
  for (size_t i = 0; i < n; ++i) {
    if (!moving[i].translates) continue;  // q_k, set by init_transforms
    const mbk::Body& body = model.bodies[moving[i].body];
    const double* q = state.position.data() + body.q_index;
    mbk::joint_motion<double>(body.joint, model.speeds, q, nullptr, m);
    set_vector(body.joint.offset + m.translation,
               transforms[i].transform.translation);  // q_k + s_k in Bj
  }
  if (transforms.size() == n) return;
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
