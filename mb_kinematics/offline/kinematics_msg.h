// mb_kinematics_msgs/BodyKinematicsArray and tf transforms from the core's Data, filled as the
// node fills them (doc/method.md 8): every vector in R; tf: a frame per moving body,
// parent = its lower body's frame (q_k + s_k and SJK); fixed joints separately, for /tf_static.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk_offline {

// Names, indices and lower bodies of every body; header.frame_id = `frame` (R's tf name).
void init_kinematics_msg(const mbk::Model& model, const std::string& frame,
                         mb_kinematics_msgs::BodyKinematicsArray& msg);
// Pose, mass center, twist and accel of every body from `data`.
void fill_kinematics_msg(const mbk::Model& model, const mbk::Data<double>& data,
                         mb_kinematics_msgs::BodyKinematicsArray& msg);

// tf frame names: `prefix` + body name, R = `prefix` + R's name.
class TfFrames {
 public:
  TfFrames(const mbk::Model& model, const std::string& prefix);
  // The transforms of the bodies on moving joints at `state` (stamp set by the caller).
  const std::vector<geometry_msgs::TransformStamped>& moving(const mbk::JointState<double>& state);
  // The transforms of the bodies on fixed joints.
  std::vector<geometry_msgs::TransformStamped> fixed() const;
  const std::string& root() const { return root_; }

 private:
  const mbk::Model& model_;
  std::string prefix_, root_;
  std::vector<int> moving_;
  std::vector<geometry_msgs::TransformStamped> transforms_;
};

}  // namespace mbk_offline
