// The offline kinematics of a recording's rows (mbk bag), block by block on a pool of threads
// started once: each worker owns an OfflineStates and takes the block's rows a chunk at a time,
// chunks in increasing order (state, checks, forward_kinematics, the floating base), so every
// row's result is the same whatever the number of threads and whichever worker computes it.
// A worker held up (a loaded machine) leaves its chunks to the others instead of holding up the
// block. The caller writes the rows of a block in order, while the pool computes the next one.
// ROS-free.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/offline/offline_kinematics.h"

namespace mbk {

// One row's outcome: its kinematics, or why it is dropped.
struct OfflineRow {
  explicit OfflineRow(const Model& model) : state(model), data(model) {}
  double stamp = 0;
  std::string drop_reason, drop_detail;  // reason empty: computed, to be written
  JointState<double> state;
  Data<double> data;
  BaseMotion base;   // the floating base's motion, when there is one
  std::string text;  // the row's output, when the batch has a formatter (set_formatter)
  // "auto": per body, the standard errors of alpha and of the mass-center acceleration
  // (OfflineStates::body_errors); empty otherwise.
  std::vector<Vec3<double>> alpha_se, acceleration_se;
  // With them, the coordinates' standard errors (OfflineStates::coordinate_errors; nq each).
  std::vector<double> joint_velocity_se, joint_acceleration_se;
};

// The odometry of a floating base (core/floating_base.h) and its accelerations.
struct FloatingBaseTrack {
  std::vector<BaseSample> samples;
  std::vector<Vec3<double>> linear_acceleration, angular_acceleration;
};

class OfflineBatch {
 public:
  // `model`, `recording` and `base` (nullptr: a fixed base) must outlive this object. Starts
  // `threads` (>= 1) workers, which wait for blocks. whole: see OfflineStates.
  OfflineBatch(const Model& model, const Recording& recording, const OfflineEstimator& estimator,
               double max_gap, const FloatingBaseTrack* base, int threads,
               const WholeRecording* whole = nullptr);
  ~OfflineBatch();  // ends the workers
  OfflineBatch(const OfflineBatch&) = delete;
  OfflineBatch& operator=(const OfflineBatch&) = delete;

  // Starts rows [begin, end) into rows[0, end - begin) (rows.size() >= end - begin) on the
  // workers and returns; finish() waits for them and returns the seconds they spent, summed.
  // One block at a time; blocks must come in increasing, non-overlapping ranges. Nothing is
  // allocated per row once each worker has computed one (except a dropped row's message); with
  // one thread, once the first block is done.
  void start(int begin, int end, std::vector<OfflineRow>& rows);
  double finish();  // rethrows what a worker threw (std::bad_alloc at --max-memory)
  double compute(int begin, int end, std::vector<OfflineRow>& rows) {
    start(begin, end, rows);
    return finish();
  }

  // Called by the worker that computed a row (not dropped), on it: output formatted on the
  // workers, beside the writing. Set before start(); must be safe to call from any thread.
  using Formatter = std::function<void(OfflineRow&)>;
  void set_formatter(Formatter f) { formatter_ = std::move(f); }
  // Rows carry their bodies' error bars (OfflineRow::alpha_se; "auto", no floating base): the
  // CSV's columns. Set before start().
  void set_body_errors(bool on) { body_errors_ = on; }

  double max_gap() const { return workers_.front().max_gap(); }
  int threads() const { return static_cast<int>(workers_.size()); }
  std::vector<CoordinateError> error_summary() const { return workers_.front().error_summary(); }
  const OfflineStates& states() const { return workers_.front(); }  // not while computing
  // Rows per block that keep one block's results, with `text_bytes` of formatted text per row,
  // within `bytes` (at least 4 per thread).
  int rows_per_block(size_t bytes, size_t text_bytes = 0) const;

 private:
  void compute_row(OfflineStates& states, int r, OfflineRow& out) const;
  void work(int worker);  // a worker's loop: wait for a block, take its chunks, repeat

  const Model& model_;
  const Recording& rec_;
  const FloatingBaseTrack* base_;
  std::vector<OfflineStates> workers_;
  Formatter formatter_;
  bool body_errors_ = false;

  // The block in flight, set by start() under mutex_.
  int begin_ = 0, rows_in_block_ = 0, chunk_ = 1;
  std::vector<OfflineRow>* out_ = nullptr;
  std::atomic<int> next_chunk_{0};
  std::mutex mutex_;
  std::condition_variable started_, finished_;
  long block_ = 0;   // blocks started; a worker runs each once
  int running_ = 0;  // workers still on the block
  bool stop_ = false;
  double seconds_ = 0;        // the workers', on the block, summed
  std::exception_ptr error_;  // what a worker threw on the block (finish() rethrows it)
  std::vector<std::thread> threads_;
};

// std::thread::hardware_concurrency(), at least 1.
int default_thread_count();

// The two blocks of rows compute_rows fills in turn. A caller that computes many ranges of rows
// (OfflineStream's chunks) keeps them, and the rows are made once.
struct RowBlocks {
  std::vector<OfflineRow> ready, next;
};

// Rows [begin, end) of `batch`, a block at a time (rows_per_block(4 MB) with the first block's
// formatted text; the first block the least), each handed to `use` in order while the workers
// compute the next block; progress(rows done) after each block. The rows are `blocks`' (else
// made for this call).
// Returns the seconds the workers spent (summed) and the seconds spent in `use`.
struct RowSeconds {
  double compute = 0, use = 0;
};
RowSeconds compute_rows(OfflineBatch& batch, const Model& model, int begin, int end,
                        const std::function<void(const OfflineRow&)>& use,
                        const std::function<void(int)>& progress, RowBlocks* blocks = nullptr);

}  // namespace mbk
