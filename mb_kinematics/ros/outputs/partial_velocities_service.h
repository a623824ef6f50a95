// ~get_partial_velocities (mb_kinematics_msgs/GetPartialVelocities, doc/method.md 9): the partial
// velocity arrays of the named bodies and their time derivatives at the latest sample, sparse
// (the independent speeds of each body's chain, mimic columns folded into their sources').
// Keeps a copy of the latest sample's coordinates and speeds (no allocation per sample); the
// arrays are computed only when asked, in the service call.
#pragma once

#include <mb_kinematics_msgs/GetPartialVelocities.h>
#include <ros/service_server.h>

#include <mutex>
#include <string>
#include <vector>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

class PartialVelocitiesService : public Output {
 public:
  static bool enabled(const NodeParams&) { return true; }
  explicit PartialVelocitiesService(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kVelocity; }  // the columns need q, y
  bool uses_data() const override { return false; }
  bool active() override { return true; }
  bool is_service() const override { return true; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  bool answer(mb_kinematics_msgs::GetPartialVelocities::Request& request,
              mb_kinematics_msgs::GetPartialVelocities::Response& response);

  const mbk::Model& model_;
  std::mutex& mutex_;  // the node's (OutputSetup::mutex), held in answer()
  std::string frame_;
  mbk::JointState<double> latest_;
  std::vector<char> published_;  // per body, of the latest sample (~missing_coordinates skip)
  ros::Time stamp_;
  bool has_sample_ = false;
  ros::ServiceServer server_;
};

}  // namespace mbk_ros
