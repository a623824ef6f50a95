// The fate of the node's input (doc/node.md: bad input): samples received, published and
// dropped, a count per class of problem (input_problem.h) and the last one, for /diagnostics
// (outputs/diagnostics_output.h); and the warnings in the log, at most one per class every 5 s.
#pragma once

#include <array>
#include <chrono>
#include <string>

#include "mb_kinematics/ros/input_problem.h"

namespace mbk_ros {

class InputTally {
 public:
  struct Counters {
    long received = 0, dropped = 0, incomplete = 0, published = 0;
    double update_seconds = 0, max_update_seconds = 0;
  };

  void received();  // a joint_states message came in
  // A sample (or a joint_accelerations or odometry message) of this class; `message` says what
  // and where. warn also logs it, throttled per class.
  void count(InputProblem problem, const std::string& message);
  void warn(InputProblem problem, const std::string& message);
  void published(double seconds);  // a sample went out, after `seconds` of work
  // A new model: the counts start from zero (the throttling of warnings goes on).
  void restart();

  const Counters& total() const { return total_; }
  const Counters& window() const { return window_; }  // since window_start()
  std::chrono::steady_clock::time_point window_start() const { return window_start_; }
  void restart_window(std::chrono::steady_clock::time_point now);  // after each report
  long problems(InputProblem problem) const { return problems_[static_cast<size_t>(problem)]; }
  const std::string& last_problem() const { return last_problem_; }

 private:
  static constexpr size_t kClasses = static_cast<size_t>(InputProblem::kCount);
  Counters total_, window_;
  std::chrono::steady_clock::time_point window_start_ = std::chrono::steady_clock::now();
  std::array<long, kClasses> problems_{};
  std::string last_problem_;
  std::array<std::chrono::steady_clock::time_point, kClasses> last_warned_{};
};

}  // namespace mbk_ros
