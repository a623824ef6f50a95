#include "mb_kinematics/offline/offline_batch.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

#include "mb_kinematics/core/finite_kinematics.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/start_threads.h"
#include "mb_kinematics/core/state_check.h"

namespace mbk {

int default_thread_count() { return std::max(1u, std::thread::hardware_concurrency()); }

OfflineBatch::OfflineBatch(const Model& model, const Recording& recording,
                           const OfflineEstimator& estimator, double max_gap,
                           const FloatingBaseTrack* base, int threads, const WholeRecording* whole)
    : model_(model), rec_(recording), base_(base) {
  workers_.reserve(std::max(1, threads));
  workers_.emplace_back(model, recording, estimator, max_gap, whole, threads);
  while (static_cast<int>(workers_.size()) < threads)
    workers_.push_back(workers_.front());  // a copy: no second scan of the rows
  // A thread that cannot start shrinks the pool to those that did; none at all is an error.
  threads_ = start_threads(
      workers_.size(), [this](std::size_t i) { work(static_cast<int>(i)); }, true);
  while (workers_.size() > threads_.size()) workers_.pop_back();  // no block started yet
}

OfflineBatch::~OfflineBatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  started_.notify_all();
  for (std::thread& t : threads_) t.join();
}

int OfflineBatch::rows_per_block(size_t bytes, size_t text_bytes) const {
  const size_t row = sizeof(OfflineRow) +
                     model_.bodies.size() * (sizeof(Mat3<double>) + 8 * sizeof(Vec3<double>)) +
                     3 * model_.nq * sizeof(double) + text_bytes;
  const int floor = 4 * threads();
  return std::max(floor, static_cast<int>(std::min<size_t>(512, bytes / row)));
}

void OfflineBatch::compute_row(OfflineStates& states, int r, OfflineRow& out) const {
  const double t = rec_.stamp[r];  // on the stamps' grid when they lie on one
  out.stamp = rec_.recorded(r);
  out.drop_reason.clear(), out.drop_detail.clear();  // a reused row keeps no earlier drop's
  const auto drop = [&](const char* reason, const std::string& detail) {
    out.drop_reason = reason;
    out.drop_detail = "sample at t = " + std::to_string(rec_.origin + out.stamp) + detail;
  };
  std::string problem = states.state_at(r, out.state);
  if (!problem.empty()) return drop("too few samples for derivatives", ": " + problem);
  problem = check_state(model_, out.state);  // NaN/Inf, |e| ~ 0, overflow
  if (!problem.empty()) return drop("state rejected (mbk::check_state)", ": " + problem);
  forward_kinematics(model_, out.state, out.data, Level::kAcceleration);
  if (base_) {
    if (!interpolate_base(base_->samples, base_->linear_acceleration, base_->angular_acceleration,
                          t, out.base))
      return drop("outside the base odometry's time span", "");
    apply_floating_base(out.base, out.data);
  }
  if (!finite_kinematics(out.data, Level::kAcceleration)) return drop("kinematics not finite", "");
  // The error bars in the model's frame; with a base, R is the odometry's: none.
  if (!body_errors_ || base_ ||
      !states.body_errors(r, out.state, out.data, out.alpha_se, out.acceleration_se)) {
    out.alpha_se.clear(), out.acceleration_se.clear();
    out.joint_velocity_se.clear(), out.joint_acceleration_se.clear();
    return;
  }
  out.joint_velocity_se.assign(model_.nq, 0.0), out.joint_acceleration_se.assign(model_.nq, 0.0);
  states.coordinate_errors(r, out.joint_velocity_se.data(), out.joint_acceleration_se.data());
}

void OfflineBatch::start(int begin, int end, std::vector<OfflineRow>& rows) {
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return running_ == 0; });  // one block at a time
  begin_ = begin;
  rows_in_block_ = std::max(0, end - begin);
  // About eight chunks per worker: small enough to share out a held-up worker's rows, large
  // enough that a worker seldom skips rows (OfflineStates then catches up its partial series).
  chunk_ = std::max(1, rows_in_block_ / (8 * threads()));
  out_ = &rows;
  next_chunk_ = 0;
  seconds_ = 0;
  running_ = threads();
  ++block_;
  started_.notify_all();
}

double OfflineBatch::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return running_ == 0; });
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  return seconds_;
}

void OfflineBatch::work(int worker) {
  long done = 0;  // the last block this worker ran
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      started_.wait(lock, [&] { return stop_ || block_ != done; });
      if (stop_) return;
      done = block_;
    }
    // The block's fields stay as start() set them until every worker is done with it.
    const auto t0 = std::chrono::steady_clock::now();
    const int chunks = (rows_in_block_ + chunk_ - 1) / chunk_;
    std::exception_ptr error;
    try {
      for (int c = next_chunk_++; c < chunks; c = next_chunk_++)
        for (int j = c * chunk_; j < std::min(rows_in_block_, (c + 1) * chunk_); ++j) {
          OfflineRow& row = (*out_)[j];
          compute_row(workers_[worker], begin_ + j, row);
          if (formatter_ && row.drop_reason.empty()) formatter_(row);
        }
    } catch (...) {  // for finish() to rethrow: an uncaught one here would abort the process
      error = std::current_exception();
      next_chunk_ = chunks;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::lock_guard<std::mutex> lock(mutex_);
    if (error && !error_) error_ = error;
    seconds_ += seconds;
    if (--running_ == 0) finished_.notify_all();
  }
}

namespace {

// The most bytes of text a row holds (OfflineRow::text, the formatter's).
size_t text_bytes(const std::vector<OfflineRow>& rows) {
  size_t most = 0;
  for (const OfflineRow& row : rows) most = std::max(most, row.text.capacity());
  return most;
}

// Waits for the block in flight; what its workers threw gives way to the caller's exception.
void wait_for(OfflineBatch& batch) {
  try {
    batch.finish();
  } catch (...) {
  }
}

}  // namespace

RowSeconds compute_rows(OfflineBatch& batch, const Model& model, int begin, int end,
                        const std::function<void(const OfflineRow&)>& use,
                        const std::function<void(int)>& progress, RowBlocks* blocks) {
  using Clock = std::chrono::steady_clock;
  RowSeconds s;
  if (begin >= end) return s;
  // The rows made are the rows computed (a short recording makes few), and a block's results,
  // with each row's formatted text (a CSV row of a large model outweighs its kinematics), stay
  // within 4 MB: the first block is small, and its texts size the others. Rows made and touched
  // once per call and never reused were most of a short run's page faults.
  RowBlocks own;
  RowBlocks& rows = blocks ? *blocks : own;
  std::vector<OfflineRow>&ready = rows.ready, &next = rows.next;
  const OfflineRow blank(model);
  int first = begin, last = std::min(end, begin + batch.rows_per_block(0));
  if (static_cast<int>(ready.size()) < last - first) ready.resize(last - first, blank);
  s.compute += batch.compute(first, last, ready);
  const int block = batch.rows_per_block(4 << 20, text_bytes(ready));
  for (;;) {
    const int after = std::min(last + block, end);
    if (last < end) {
      if (static_cast<int>(next.size()) < after - last) next.resize(after - last, blank);
      batch.start(last, after, next);
    }
    const auto t0 = Clock::now();
    try {
      for (int r = first; r < last; ++r) use(ready[r - first]);
      progress(last);
    } catch (...) {  // a refused row (a bag's stamp): the block in flight writes into `next`
      if (last < end) wait_for(batch);
      throw;
    }
    s.use += std::chrono::duration<double>(Clock::now() - t0).count();
    if (last == end) return s;
    s.compute += batch.finish();
    std::swap(ready, next);
    first = last, last = after;
  }
}

}  // namespace mbk
