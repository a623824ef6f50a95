#include "mb_kinematics/ros/outputs/diagnostics_output.h"

#include <algorithm>
#include <mutex>
#include <utility>

#include "mb_kinematics/core/error_indicators.h"

namespace mbk_ros {
namespace {

std::string names_or_none(const std::vector<std::string>& names) {
  return names.empty() ? "none" : join_names(names, 100);
}

// ~missing_coordinates: what is missing and what is done about it; returns the line (empty:
// nothing missing).
std::string report_coverage(const CoordinateCoverage& c,
                            diagnostic_updater::DiagnosticStatusWrapper& status) {
  const bool skip = c.mode() == MissingCoordinates::kSkip;
  status.add("missing_coordinates", skip                                    ? "skip"
                                    : c.mode() == MissingCoordinates::kWait ? "wait"
                                                                            : "zero");
  status.add("joints never received", names_or_none(c.never()));
  status.add("joints stale (no sample for ~max_sample_gap)", names_or_none(c.stale()));
  status.add("bodies left out", names_or_none(c.left_out()));
  const bool none = skip || !c.ready();  // skip: left out; wait: nothing published yet
  status.add("bodies from invented or held values",
             names_or_none(none ? std::vector<std::string>() : c.affected()));
  return c.describe();
}

// `from`'s values into `to`, a state of the same model, a vector at a time in one memmove
// (Eigen's assignment goes two numbers at a time): every sample's.
void copy_values(const mbk::JointState<double>& from, mbk::JointState<double>& to) {
  for (auto [a, b] :
       {std::pair(&from.position, &to.position), std::pair(&from.velocity, &to.velocity),
        std::pair(&from.acceleration, &to.acceleration)})
    std::copy(a->data(), a->data() + a->size(), b->data());
}

}  // namespace

DiagnosticsOutput::DiagnosticsOutput(const OutputSetup& setup)
    : model_(setup.model),
      estimator_(setup.params.acceleration_estimator),
      tally_(setup.tally),
      coverage_(setup.coverage),
      previous_state_(setup.model),
      updater_(setup.nh, setup.pnh) {
  updater_.setHardwareID("none");
  updater_.add("Joint state input", this, &DiagnosticsOutput::diagnose);
  timer_ = setup.nh.createTimer(ros::Duration(1.0),
                                [this, &mutex = setup.mutex](const ros::TimerEvent&) {
                                  std::lock_guard<std::mutex> lock(mutex);
                                  updater_.update();
                                });
}

void DiagnosticsOutput::publish(const ros::Time& stamp, const Sample& sample) {
  state_ = &sample.state;
  data_ = &sample.data;
  const double t = stamp.toSec();
  const bool full = sample.level == mbk::Level::kAcceleration;
  if (full && previous_stamp_ >= 0 && t > previous_stamp_) {  // no prediction across a jump back
    const double residual =
        mbk::prediction_residual(previous_state_, sample.state, t - previous_stamp_);
    max_residual_ = std::max(max_residual_, residual);
  }
  copy_values(sample.state, previous_state_);  // same sizes
  previous_stamp_ = full ? t : -1;
}

void DiagnosticsOutput::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const auto now = std::chrono::steady_clock::now();
  const InputTally::Counters& window = tally_.window();
  const InputTally::Counters& total = tally_.total();
  const std::string& last_problem = tally_.last_problem();
  const double elapsed = std::chrono::duration<double>(now - tally_.window_start()).count();
  const double rate = elapsed > 0 ? window.received / elapsed : 0.0;
  const double mean = window.published ? window.update_seconds / window.published : 0.0;
  status.add("input rate (Hz)", rate);
  status.add("update time per sample, mean (us)", mean * 1e6);
  status.add("update time per sample, max (us)", window.max_update_seconds * 1e6);
  status.add("samples received", total.received);
  status.add("samples published", total.published);
  status.add("samples dropped (bad input)", total.dropped);
  status.add("samples waiting for joints", total.incomplete);
  status.add("last problem", last_problem.empty() ? "none" : last_problem);
  for (size_t p = 0; p < static_cast<size_t>(InputProblem::kCount); ++p)
    status.add(diagnostic_key(static_cast<InputProblem>(p)),
               tally_.problems(static_cast<InputProblem>(p)));
  // Cheap error indicators (mb_kinematics/core/error_indicators.h; doc/error_vs_runtime.md).
  status.add("rotation orthonormality drift", data_ ? mbk::orthonormality_drift(*data_) : 0.0);
  status.add("Euler parameter norm error", state_ ? mbk::euler_norm_error(model_, *state_) : 0.0);
  status.add("estimator residual, max (rad or m)", max_residual_);
  status.add("acceleration estimator", estimator_);
  const std::string missing = report_coverage(coverage_, status);
  if (window.dropped > 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "dropping samples: " + last_problem);
  else if (window.received == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no joint_states received");
  else if (window.published == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, last_problem);
  else if (!missing.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "publishing; " + missing);
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "publishing");
  max_residual_ = 0;
  tally_.restart_window(now);
}

}  // namespace mbk_ros
