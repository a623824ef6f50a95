// A progress bar for long work (mbk bag): on stderr, only when stderr is a terminal; percent,
// items per second and time left, redrawn at most 10 times a second. ROS-free.
#pragma once

#include <chrono>
#include <string>

namespace mbk {

class Progress {
 public:
  // `label` says what is counted ("reading", "computing").
  explicit Progress(const std::string& label, bool enabled);
  ~Progress();
  void update(long done, long total);
  void finish();  // clears the line

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

// Whether stderr is a terminal.
bool stderr_is_terminal();

}  // namespace mbk
