// tf transforms from the core's Data, made as the node makes them (doc/method.md 8): a frame per
// moving body, parent = its lower body's frame (q_k + s_k and SJK); fixed joints separately, for
// /tf_static. body_kinematics is filled by the node's own mb_kinematics/messages/body_kinematics.h.
#pragma once

#include <geometry_msgs/TransformStamped.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk_offline {

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
