// core/split_runs.h: every run done once, on a pool that shrinks when a thread cannot start.
#include "mb_kinematics/core/split_runs.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <numeric>
#include <stdexcept>
#include <vector>

#include "test/support/address_space.h"

namespace {

// Runs `runs` runs over as many items; true if each item was written once, by its own run.
bool every_item_once(int runs) {
  std::vector<int> hits(static_cast<std::size_t>(runs), 0), owner(hits.size(), -1);
  mbk::split_runs(hits.size(), runs, [&](std::size_t t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) ++hits[i], owner[i] = static_cast<int>(t);
  });
  for (std::size_t i = 0; i < hits.size(); ++i)
    if (hits[i] != 1 || owner[i] != static_cast<int>(i)) return false;
  return true;
}

TEST(SplitRuns, EveryRunOnceOnAnyThreadCount) {
  for (int runs : {1, 2, 7, 64}) EXPECT_TRUE(every_item_once(runs)) << runs;
}

TEST(SplitRuns, AnExceptionOfARunReachesTheCaller) {
  EXPECT_THROW(mbk::split_runs(10, 4,
                               [](std::size_t t, std::size_t, std::size_t) {
                                 if (t == 2) throw std::runtime_error("run 2");
                               }),
               std::runtime_error);
}

// 1,000 threads under an address space 256 MB above what the process holds: their stacks (8 MB
// each by default) do not fit, std::thread throws after a few dozen, and the runs left go on this
// thread. Without that, the throw with joinable threads in the pool was std::terminate.
TEST(SplitRuns, ThreadsThatCannotStartShrinkThePool) {
#if defined(__SANITIZE_ADDRESS__)  // AddressSanitizer's shadow rules out an address space cap
  GTEST_SKIP() << "no address space cap under AddressSanitizer";
#else
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    rlimit limit{};
    getrlimit(RLIMIT_AS, &limit);
    limit.rlim_cur = static_cast<rlim_t>(mbk_test::address_space() + (256L << 20));
    if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
    _exit(every_item_once(1000) ? 0 : 2);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
#endif
}

}  // namespace
