// The output bag of mbk bag: /body_kinematics (mb_kinematics_msgs/BodyKinematicsArray) and /tf
// at each sample's own stamp, /tf_static once (at the first sample's stamp) when the model has
// fixed joints; written with the rosbag C++ API.
#pragma once

#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/messages/frames.h"
#include "mb_kinematics/messages/tf.h"

namespace mbk_offline {

class BagOutput {
 public:
  // Throws std::invalid_argument if `path` cannot be written. `prefix` goes before every frame
  // taken from the model. With a floating base, `base_frame` names R (the odometry's frame) and
  // each write gets the root frame's pose in it. body_kinematics lists the bodies of
  // `kinematics_model` (with a base: with_floating_base(model), as the node), `data` is of it;
  // its system.missing_segments are `missing_segments` (the model file's: mbk::ModelFile).
  BagOutput(const std::string& path, const mbk::Model& model, const std::string& prefix,
            const std::string& base_frame, const mbk::Model& kinematics_model,
            const std::vector<std::string>& missing_segments = {});
  ~BagOutput();
  BagOutput(const BagOutput&) = delete;
  BagOutput& operator=(const BagOutput&) = delete;
  // Both throw std::runtime_error naming the path when the disk refuses the data.
  void write(double stamp, const mbk::JointState<double>& state, const mbk::Data<double>& data,
             const mbk::BaseMotion* base = nullptr);
  void close();
  // The whole seconds the stamps given are counted from (Recording::origin); set before writing.
  void set_time_origin(double seconds) { origin_ = seconds; }

 private:
  void write_sample(double stamp, const mbk::JointState<double>& state,
                    const mbk::Data<double>& data, const mbk::BaseMotion* base);
  void abandon();
  [[noreturn]] void fail(const rosbag::BagException& e);

  const mbk::Model& model_;
  const mbk::Model& kinematics_model_;
  std::string path_;
  std::unique_ptr<rosbag::Bag> bag_;  // null once writing failed (abandon())
  mbk_messages::FrameNames names_;
  std::vector<mbk_messages::TfJoint> moving_;  // the bodies on joints with coordinates
  mb_kinematics_msgs::BodyKinematicsArray kinematics_;
  tf2_msgs::TFMessage tf_;  // moving_'s transforms, then R -> the root frame with a base
  bool static_written_ = false;
  double origin_ = 0;
};

}  // namespace mbk_offline
