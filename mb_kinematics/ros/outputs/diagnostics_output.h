// /diagnostics (diagnostic_updater, every ~diagnostic_period): the input rate, the update time
// per sample, what was received, published and dropped, the last problem, and the cheap error
// indicators of the README's "Error against run time" (error_indicators.h). The node reports
// its input's fate here; publish() takes each computed sample's estimator residual.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>

#include <chrono>
#include <string>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

class DiagnosticsOutput : public Output {
 public:
  DiagnosticsOutput(const OutputSetup& setup, ros::NodeHandle pnh);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }  // reads the latest data when it reports
  bool active() override { return true; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

  void received();                           // a joint_states message came in
  void dropped(const std::string& problem);  // a sample was refused
  void waiting(const std::string& problem);  // a sample waits for joints never received
  void problem(const std::string& problem);  // something else went wrong (no sample lost)
  void published(double seconds);            // a sample went out, after `seconds` of work

 private:
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  const mbk::Model& model_;
  std::string estimator_;
  const mbk::JointState<double>* state_ = nullptr;  // the latest sample's
  const mbk::Data<double>* data_ = nullptr;
  mbk::JointState<double> previous_state_;  // the last sample, for the residual
  double previous_stamp_ = -1;              // its stamp; < 0: none
  diagnostic_updater::Updater updater_;
  ros::Timer timer_;
  struct Counters {
    long received = 0, dropped = 0, incomplete = 0, published = 0;
    double update_seconds = 0, max_update_seconds = 0;
    double max_residual = 0;  // mbk::prediction_residual, over the samples
  } total_, window_;
  std::chrono::steady_clock::time_point window_start_;
  std::string last_problem_;
};

}  // namespace mbk_ros
