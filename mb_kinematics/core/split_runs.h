// One job shared out in contiguous runs among threads: the batch kinematics' samples, the
// derivative estimators' samples and series. Each run writes only its own outputs, so the results
// are the same bits on any thread count.
#pragma once

#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include "mb_kinematics/core/start_threads.h"

namespace mbk {

// Runs job(t, begin, end) on `threads` contiguous runs of [0, items), the last on this thread;
// an exception of a run (std::bad_alloc) is rethrown here after every run has ended. A thread
// that cannot start shrinks the pool (start_threads): its run and the later ones go on this
// thread, with the same results.
template <typename Job>
void split_runs(std::size_t items, int threads, const Job& job) {
  const std::size_t n = static_cast<std::size_t>(threads);
  std::vector<std::exception_ptr> errors(n);
  const auto run = [&](std::size_t t) {
    try {
      job(t, items * t / n, items * (t + 1) / n);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool = start_threads(n - 1, run, false);
  for (std::size_t t = pool.size(); t < n; ++t) run(t);
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace mbk
