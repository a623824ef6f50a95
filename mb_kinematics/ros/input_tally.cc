#include "mb_kinematics/ros/input_tally.h"

#include <ros/console.h>

#include <algorithm>

#include "mb_kinematics/core/printable.h"

namespace mbk_ros {
namespace {

constexpr double kThrottle = 5.0;  // seconds between repeats of one warning

}  // namespace

void InputTally::received() {
  ++total_.received;
  ++window_.received;
}

void InputTally::count(InputProblem problem, const std::string& message) {
  ++problems_[static_cast<size_t>(problem)];
  last_problem_ = message;
  for (Counters* c : {&total_, &window_}) {
    if (drops_sample(problem)) ++c->dropped;
    if (problem == InputProblem::kMissingJoints) ++c->incomplete;
  }
}

void InputTally::warn(InputProblem problem, const std::string& message) {
  count(problem, message);
  const auto now = std::chrono::steady_clock::now();
  auto& last = last_warned_[static_cast<size_t>(problem)];
  if (last != std::chrono::steady_clock::time_point() &&
      now - last < std::chrono::duration<double>(kThrottle))
    return;
  last = now;
  ROS_WARN_STREAM(mbk::printable(message));
}

void InputTally::published(double seconds) {
  for (Counters* c : {&total_, &window_}) {
    ++c->published;
    c->update_seconds += seconds;
    c->max_update_seconds = std::max(c->max_update_seconds, seconds);
  }
}

void InputTally::restart() {
  total_ = window_ = Counters();
  window_start_ = std::chrono::steady_clock::now();
  problems_.fill(0);
  last_problem_.clear();
}

void InputTally::restart_window(std::chrono::steady_clock::time_point now) {
  window_ = Counters();
  window_start_ = now;
}

}  // namespace mbk_ros
