// tf from the joint state (doc/method.md 8), for the node's /tf and /tf_static and mbk bag's:
// a frame per body, parent = its lower body's frame, the relative transform q_k + s_k and SJK
// of its joint alone; for mbk bag --base-odometry also the floating base's pose in the
// odometry's frame. Moving joints every sample (nothing allocated), fixed joints once.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>

#include <Eigen/Geometry>
#include <vector>

#include "mb_kinematics/core/floating_base.h"
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
  // A revolute joint whose C_k is the identity (every URDF joint without rpy): SJK is the turn
  // (cos(q/2), sin(q/2) axis) alone, its sine and cosine taken with the other such joints'.
  bool plain_turn;
  // The body's first coordinate and its joint's axis, copied here so that a sample's loop over
  // the joints reads them without going through the model's bodies.
  int q_index;
  Eigen::Vector3d axis;
};
TfJoint tf_joint(const mbk::Model& model, int body);

// The bodies on joints with coordinates, from body `first` on.
std::vector<int> moving_bodies(const mbk::Model& model, int first = 1);

// `bodies`' joints into `moving` and a transform each into `transforms`, frames set, and the
// translation q_k of each joint that does not translate (fill_transforms leaves it). With a
// `base_frame` (the odometry's frame of a floating base), one transform more, last:
// base_frame -> names.root(), the model's root frame.
void init_transforms(const mbk::Model& model, const FrameNames& names,
                     const std::vector<int>& bodies, std::vector<TfJoint>& moving,
                     std::vector<geometry_msgs::TransformStamped>& transforms,
                     const std::string& base_frame = "");

// The relative transforms of the `moving` bodies at `stamp` into `transforms` (made by
// init_transforms: frames and constant translations set): nothing allocated. The base's transform,
// if init_transforms made one, gets the stamp and, with `base`, the root frame's pose in the
// odometry's frame.
void fill_transforms(const mbk::Model& model, const mbk::JointState<double>& state,
                     const std::vector<TfJoint>& moving, const ros::Time& stamp,
                     std::vector<geometry_msgs::TransformStamped>& transforms,
                     const mbk::BaseMotion* base = nullptr);

// The transforms of the bodies on fixed joints, at `stamp` (/tf_static).
std::vector<geometry_msgs::TransformStamped> fixed_transforms(const mbk::Model& model,
                                                              const FrameNames& names,
                                                              const ros::Time& stamp);

}  // namespace mbk_messages
