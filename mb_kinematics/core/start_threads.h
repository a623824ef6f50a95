// Starting a pool of threads when some may not start (no address space for a thread's stack, a
// process limit): the one policy of split_runs (core/split_runs.h) and the offline batch
// (offline/offline_batch.h).
#pragma once

#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace mbk {

// Threads running run(0), run(1), ..., run(n - 1), as many as start: the first that cannot
// start (std::system_error; std::bad_alloc) shrinks the pool to those before it. None at all
// when `need_one` is an error: std::system_error with the system's code (under mbk bag
// --max-memory, EAGAIN, which names the cap), "cannot start a computing thread", or the
// std::bad_alloc as thrown.
template <typename Run>
std::vector<std::thread> start_threads(std::size_t n, const Run& run, bool need_one) {
  std::vector<std::thread> pool;
  try {
    pool.reserve(n);
    for (std::size_t t = 0; t < n; ++t) pool.emplace_back(run, t);
  } catch (const std::exception& e) {
    if (!need_one || !pool.empty()) return pool;
    if (const auto* system = dynamic_cast<const std::system_error*>(&e))
      throw std::system_error(system->code(), "cannot start a computing thread");
    throw;
  }
  return pool;
}

}  // namespace mbk
