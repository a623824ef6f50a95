#include "mb_kinematics/ros/outputs/diagnostics_output.h"

#include <algorithm>

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

}  // namespace

DiagnosticsOutput::DiagnosticsOutput(const OutputSetup& setup, ros::NodeHandle pnh)
    : model_(setup.model),
      estimator_(setup.params.acceleration_estimator),
      previous_state_(setup.model),
      updater_(setup.nh, pnh),
      window_start_(std::chrono::steady_clock::now()) {
  updater_.setHardwareID("none");
  updater_.add("Joint state input", this, &DiagnosticsOutput::diagnose);
  timer_ = setup.nh.createTimer(ros::Duration(1.0),
                                [this](const ros::TimerEvent&) { updater_.update(); });
}

void DiagnosticsOutput::publish(const ros::Time& stamp, const Sample& sample) {
  state_ = &sample.state;
  data_ = &sample.data;
  const double t = stamp.toSec();
  const bool full = sample.level == mbk::Level::kAcceleration;
  if (full && previous_stamp_ >= 0 && t > previous_stamp_) {  // no prediction across a jump back
    const double residual =
        mbk::prediction_residual(previous_state_, sample.state, t - previous_stamp_);
    for (Counters* c : {&total_, &window_}) c->max_residual = std::max(c->max_residual, residual);
  }
  previous_state_ = sample.state;
  previous_stamp_ = full ? t : -1;
}

void DiagnosticsOutput::received() {
  ++total_.received;
  ++window_.received;
}

void DiagnosticsOutput::count(InputProblem problem, const std::string& message) {
  ++problems_[static_cast<size_t>(problem)];
  last_problem_ = message;
  for (Counters* c : {&total_, &window_}) {
    if (drops_sample(problem)) ++c->dropped;
    if (problem == InputProblem::kMissingJoints) ++c->incomplete;
  }
}

void DiagnosticsOutput::published(double seconds) {
  for (Counters* c : {&total_, &window_}) {
    ++c->published;
    c->update_seconds += seconds;
    c->max_update_seconds = std::max(c->max_update_seconds, seconds);
  }
}

void DiagnosticsOutput::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - window_start_).count();
  const double rate = elapsed > 0 ? window_.received / elapsed : 0.0;
  const double mean = window_.published ? window_.update_seconds / window_.published : 0.0;
  status.add("input rate (Hz)", rate);
  status.add("update time per sample, mean (us)", mean * 1e6);
  status.add("update time per sample, max (us)", window_.max_update_seconds * 1e6);
  status.add("samples received", total_.received);
  status.add("samples published", total_.published);
  status.add("samples dropped (bad input)", total_.dropped);
  status.add("samples waiting for joints", total_.incomplete);
  status.add("last problem", last_problem_.empty() ? "none" : last_problem_);
  for (size_t p = 0; p < problems_.size(); ++p)
    status.add(diagnostic_key(static_cast<InputProblem>(p)), problems_[p]);
  // Cheap error indicators (mb_kinematics/core/error_indicators.h; README, work-precision).
  status.add("rotation orthonormality drift", data_ ? mbk::orthonormality_drift(*data_) : 0.0);
  status.add("Euler parameter norm error", state_ ? mbk::euler_norm_error(model_, *state_) : 0.0);
  status.add("estimator residual, max (rad or m)", window_.max_residual);
  status.add("acceleration estimator", estimator_);
  const std::string missing = coverage_ ? report_coverage(*coverage_, status) : "";
  if (window_.dropped > 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "dropping samples: " + last_problem_);
  else if (window_.received == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no joint_states received");
  else if (window_.published == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, last_problem_);
  else if (!missing.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "publishing; " + missing);
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "publishing");
  window_ = Counters();
  window_start_ = now;
}

}  // namespace mbk_ros
