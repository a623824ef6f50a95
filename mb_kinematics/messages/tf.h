// tf from the joint state (doc/method.md 8), for the node's /tf and /tf_static and mbk bag's:
// a frame per body, parent = its lower body's frame, the relative transform q_k + s_k and SJK
// of its joint alone. Moving joints every sample (nothing allocated), fixed joints once.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>

#include <Eigen/Geometry>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/messages/frames.h"

namespace mbk_messages {

// A body on a joint with coordinates, as /tf publishes it: SJK from the joint's quaternion
// (mbk::joint_quaternion) after C_k's, made once; s_k only for joints that translate.
struct TfJoint {
  int body;
  Eigen::Quaterniond offset;  // C_k
  bool translates;            // prismatic, planar, free joints: s_k from mbk::joint_motion
};
TfJoint tf_joint(const mbk::Model& model, int body);

// The bodies on joints with coordinates, from body `first` on.
std::vector<int> moving_bodies(const mbk::Model& model, int first = 1);

// `bodies`' joints into `moving` and a transform each into `transforms`, frames set.
void init_transforms(const mbk::Model& model, const FrameNames& names,
                     const std::vector<int>& bodies, std::vector<TfJoint>& moving,
                     std::vector<geometry_msgs::TransformStamped>& transforms);

// The relative transforms of the `moving` bodies at `stamp` into `transforms` (one per moving
// body, frames already set): nothing allocated.
void fill_transforms(const mbk::Model& model, const mbk::JointState<double>& state,
                     const std::vector<TfJoint>& moving, const ros::Time& stamp,
                     std::vector<geometry_msgs::TransformStamped>& transforms);

// The transforms of the bodies on fixed joints, at `stamp` (/tf_static).
std::vector<geometry_msgs::TransformStamped> fixed_transforms(const mbk::Model& model,
                                                              const FrameNames& names,
                                                              const ros::Time& stamp);

}  // namespace mbk_messages
