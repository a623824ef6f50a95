// The offline kinematics of a recording's rows (mbk bag), block by block on several threads:
// each worker owns an OfflineStates and computes its own run of each block's rows (state,
// checks, forward_kinematics, the floating base), so every row's result is the same whatever
// the number of threads. The caller writes the rows of a block in order. ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/offline_kinematics.h"

namespace mbk {

// One row's outcome: its kinematics, or why it is dropped.
struct OfflineRow {
  explicit OfflineRow(const Model& model) : state(model), data(model) {}
  double stamp = 0;
  std::string drop_reason, drop_detail;  // reason empty: computed, to be written
  JointState<double> state;
  Data<double> data;
  BaseMotion base;  // the floating base's motion, when there is one
};

// The odometry of a floating base (core/floating_base.h) and its accelerations.
struct FloatingBaseTrack {
  std::vector<BaseSample> samples;
  std::vector<Vec3<double>> linear_acceleration, angular_acceleration;
};

class OfflineBatch {
 public:
  // `model`, `recording` and `base` (nullptr: a fixed base) must outlive this object. threads
  // >= 1.
  OfflineBatch(const Model& model, const Recording& recording, const OfflineEstimator& estimator,
               double max_gap, const FloatingBaseTrack* base, int threads);

  // Rows [begin, end) into rows[0, end - begin) (rows.size() >= end - begin). Calls must come
  // in increasing, non-overlapping ranges. Returns the seconds the workers spent, summed. With
  // one thread nothing is allocated once the first block is done (except a dropped row's message).
  double compute(int begin, int end, std::vector<OfflineRow>& rows);

  double max_gap() const { return workers_.front().max_gap(); }
  int threads() const { return static_cast<int>(workers_.size()); }
  // Rows per block that keep one block's results within `bytes` (at least 4 per thread).
  int rows_per_block(size_t bytes) const;

 private:
  void compute_row(OfflineStates& states, int r, OfflineRow& out) const;

  const Model& model_;
  const Recording& rec_;
  const FloatingBaseTrack* base_;
  std::vector<OfflineStates> workers_;
  std::vector<double> seconds_;  // per worker, of the last compute()
};

// std::thread::hardware_concurrency(), at least 1.
int default_thread_count();

}  // namespace mbk
