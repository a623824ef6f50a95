// core/start_threads.h: a pool that shrinks to the threads that started; none at all keeps the
// system's error when one is needed. The threads cannot start here because the address space is
// capped (RLIMIT_AS) a little above what the process holds, in a child process.
#include "mb_kinematics/core/start_threads.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "test/support/address_space.h"

namespace {

// The exit status of `check` run in a child whose address space is capped `room` bytes above
// what it holds (an 8 MB thread stack needs more than 1 MB), or not capped (room < 0). Every
// test starts its threads in a child: a thread ended in this process would leave its stack in
// glibc's cache, where a capped child would find room for a thread.
template <typename Check>
int in_child(long room, const Check& check) {
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    rlimit limit{};
    getrlimit(RLIMIT_AS, &limit);
    limit.rlim_cur = static_cast<rlim_t>(mbk_test::address_space() + room);
    if (room >= 0 && setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
    _exit(check());
  }
  int status = 0;
  if (waitpid(child, &status, 0) != child || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

// Joins the threads of `pool`; their count.
std::size_t joined(std::vector<std::thread> pool) {
  for (std::thread& thread : pool) thread.join();
  return pool.size();
}

TEST(StartThreads, EveryThreadRunsItsIndex) {
  EXPECT_EQ(in_child(-1,
                     [] {
                       std::atomic<int> sum{0};
                       const auto add = [&](std::size_t t) { sum += static_cast<int>(t) + 1; };
                       return joined(mbk::start_threads(5, add, true)) == 5 && sum == 15 ? 0 : 2;
                     }),
            0);
}

#if !defined(__SANITIZE_ADDRESS__)  // AddressSanitizer's shadow rules out an address space cap
// No room for any stack: without `need_one` an empty pool (the caller runs the work itself);
// with it one error that keeps the system's code (EAGAIN: mbk bag names its --max-memory cap).
TEST(StartThreads, NoThreadAtAllIsAnErrorOnlyWhenOneIsNeeded) {
  const auto nothing = [](std::size_t) {};
  const auto none = [&] { return joined(mbk::start_threads(4, nothing, false)) == 0 ? 0 : 2; };
  EXPECT_EQ(in_child(1L << 20, none), 0);
  const auto needed = [&] {
    try {
      return joined(mbk::start_threads(4, nothing, true)) == 0 ? 6 : 7;
    } catch (const std::system_error& e) {
      const bool named = std::string(e.what()).rfind("cannot start a computing thread", 0) == 0;
      return named && e.code() == std::errc::resource_unavailable_try_again ? 0 : 4;
    } catch (...) {
      return 5;
    }
  };
  EXPECT_EQ(in_child(1L << 20, needed), 0);
}
#endif

}  // namespace
