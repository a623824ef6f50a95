#include "mb_kinematics/offline/temporary_files.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace mbk_offline {
namespace {

constexpr int kSlots = 16;         // a run has at most four outputs at once
constexpr size_t kPathMax = 4096;  // PATH_MAX on Linux

// A slot is free (0), being filled (1) or holds a path to remove (2).
struct Slot {
  std::atomic<int> state{0};
  char path[kPathMax];
};

Slot slots[kSlots];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction earlier[3];

void remove_and_reraise(int signal) {
  const int saved = errno;
  for (Slot& slot : slots)
    if (slot.state.load() == 2) unlink(slot.path);
  for (int i = 0; i < 3; ++i)
    if (kSignals[i] == signal) sigaction(signal, &earlier[i], nullptr);
  errno = saved;
  raise(signal);  // delivered when this handler returns, with the earlier action
}

}  // namespace

void remove_temporaries_on_signals() {
  static std::atomic<bool> installed{false};
  if (installed.exchange(true)) return;
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = remove_and_reraise;
  sigemptyset(&action.sa_mask);
  for (int signal : kSignals) sigaddset(&action.sa_mask, signal);
  for (int i = 0; i < 3; ++i) {
    sigaction(kSignals[i], nullptr, &earlier[i]);
    // A signal the process was started ignoring (nohup, a supervisor) stays ignored: handling it
    // would remove the files of a run that goes on, which then fails to rename them.
    const bool ignored = !(earlier[i].sa_flags & SA_SIGINFO) && earlier[i].sa_handler == SIG_IGN;
    if (!ignored) sigaction(kSignals[i], &action, nullptr);
  }
}

int record_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int free = 0;
    if (!slots[i].state.compare_exchange_strong(free, 1)) continue;
    std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
    slots[i].state.store(2);
    return i;
  }
  return -1;
}

void forget_temporary(int slot) {
  if (slot >= 0 && slot < kSlots) slots[slot].state.store(0);
}

}  // namespace mbk_offline
