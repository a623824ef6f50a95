// /diagnostics (diagnostic_updater, every ~diagnostic_period): the input rate, the update time
// per sample, what was received, published and dropped, the last problem, and the cheap error
// indicators of doc/error_vs_runtime.md (error_indicators.h), and a count per
// class of dropped, ignored, repaired or waiting input (input_problem.h): the node's input
// tallies its fate (input_tally.h), this reports it with what ~missing_coordinates makes of the
// coordinates missing (coordinate_coverage.h); publish() takes each computed sample's
// estimator residual. Always enabled; it needs no R (made at start, before ~base_odometry's).
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>

#include <string>

#include "mb_kinematics/ros/coordinate_coverage.h"
#include "mb_kinematics/ros/input_tally.h"
#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

class DiagnosticsOutput : public Output {
 public:
  static bool enabled(const NodeParams&) { return true; }
  explicit DiagnosticsOutput(const OutputSetup& setup);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }  // reads the latest data when it reports
  bool active() override { return true; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  const mbk::Model& model_;
  std::string estimator_;
  const mbk::JointState<double>* state_ = nullptr;  // the latest sample's
  const mbk::Data<double>* data_ = nullptr;
  InputTally& tally_;
  const CoordinateCoverage& coverage_;
  mbk::JointState<double> previous_state_;  // the last sample, for the residual
  double previous_stamp_ = -1;              // its stamp; < 0: none
  double max_residual_ = 0;  // mbk::prediction_residual, over the samples since the last report
  diagnostic_updater::Updater updater_;
  ros::Timer timer_;
};

}  // namespace mbk_ros
