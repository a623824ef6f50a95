// tf frame names, for the node (~frame_prefix) and mbk bag (--frame-prefix) alike: the prefix
// goes before every frame taken from the model (its R and its bodies), never before a frame
// the user names (~frame_id, an odometry's frame).
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk_messages {

// The model's own R under `prefix`.
inline std::string model_frame(const mbk::Model& model, const std::string& prefix) {
  return prefix + model.frame;
}

// The frames of a model's bodies under `prefix`; R is `root` (model_frame or a frame named
// by the user).
class FrameNames {
 public:
  FrameNames(const mbk::Model& model, const std::string& prefix, const std::string& root)
      : model_(model), prefix_(prefix), root_(root) {}
  const std::string& root() const { return root_; }
  // Body k (1..N).
  std::string body(int k) const { return prefix_ + model_.bodies[k].name; }
  // Body k's lower body: R for L(k) = 0.
  std::string lower(int k) const {
    const int j = model_.bodies[k].lower;
    return j ? body(j) : root_;
  }

 private:
  const mbk::Model& model_;
  std::string prefix_, root_;
};

}  // namespace mbk_messages
