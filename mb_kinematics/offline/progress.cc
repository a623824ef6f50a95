#include "mb_kinematics/offline/progress.h"

#include <unistd.h>

#include <cstdio>

namespace mbk {

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

Progress::Progress(const std::string& label, bool enabled)
    : label_(label), enabled_(enabled), start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() { finish(); }

void Progress::update(long done, long total) {
  if (!enabled_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(100) && done < total) return;
  last_ = now;
  drawn_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0;
  const double left = rate > 0 ? (total - done) / rate : 0;
  const int width = 30, filled = static_cast<int>(width * done / total);
  std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%  %.0f samples/s  %.0f s left  ", label_.c_str(),
               filled, "==============================", width - filled, "", 100.0 * done / total,
               rate, left);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", 100, "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace mbk
