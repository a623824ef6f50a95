// /diagnostics (diagnostic_updater, every ~diagnostic_period): the input rate, the update time
// per sample, what was received, published and dropped, the last problem, and the cheap error
// indicators of the README's "Error against run time" (error_indicators.h), and a count per
// class of dropped, ignored, repaired or waiting input (input_problem.h). The node reports its
// input's fate here; publish() takes each computed sample's estimator residual.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>

#include <array>
#include <chrono>
#include <string>

#include "mb_kinematics/ros/coordinate_coverage.h"
#include "mb_kinematics/ros/input_problem.h"
#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

class DiagnosticsOutput : public Output {
 public:
  DiagnosticsOutput(const OutputSetup& setup, ros::NodeHandle pnh);
  mbk::Level level() const override { return mbk::Level::kPose; }
  bool uses_data() const override { return false; }  // reads the latest data when it reports
  bool active() override { return true; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

  void received();  // a joint_states message came in
  // A sample (or a joint_accelerations message) of this class; `message` says what and where.
  void count(InputProblem problem, const std::string& message);
  void published(double seconds);  // a sample went out, after `seconds` of work
  // Reports what `coverage` says is missing (~missing_coordinates); it must outlive this.
  void watch(const CoordinateCoverage& coverage) { coverage_ = &coverage; }

 private:
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  const mbk::Model& model_;
  std::string estimator_;
  const mbk::JointState<double>* state_ = nullptr;  // the latest sample's
  const mbk::Data<double>* data_ = nullptr;
  const CoordinateCoverage* coverage_ = nullptr;
  mbk::JointState<double> previous_state_;  // the last sample, for the residual
  double previous_stamp_ = -1;              // its stamp; < 0: none
  diagnostic_updater::Updater updater_;
  ros::Timer timer_;
  struct Counters {
    long received = 0, dropped = 0, incomplete = 0, published = 0;
    double update_seconds = 0, max_update_seconds = 0;
    double max_residual = 0;  // mbk::prediction_residual, over the samples
  } total_, window_;
  std::array<long, static_cast<size_t>(InputProblem::kCount)> problems_{};  // since start
  std::chrono::steady_clock::time_point window_start_;
  std::string last_problem_;
};

}  // namespace mbk_ros
