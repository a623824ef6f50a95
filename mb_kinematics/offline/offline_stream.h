// mbk bag on a recording of any length in bounded memory: rows come in one at a time (from
// RecordingBuilder::stream_to), are kept only while an estimate still to compute can reach them
// (OfflineReach of the estimator), and are computed by an OfflineBatch and handed out in order a
// chunk at a time. Every row's result is the same, bit for bit, as OfflineBatch's over the whole
// recording, given that recording's max_gap and velocities (RecordingSurvey, a first pass).
// For recordings whose every coordinate is in every row or in none (a mimic left to its rule); no
// joint_accelerations, no floating base: mbk bag holds the whole recording for the others.
// ROS-free.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "mb_kinematics/offline/offline_batch.h"

namespace mbk {

// What the computation of a whole recording depends on beyond one estimate's reach, gathered
// row by row (a first pass over the input): in bounded memory but for the intervals, one entry
// per distinct interval between stamps (a few at a steady rate).
struct RecordingSurvey {
  // keep_intervals false: the user gave max_gap; the intervals are not counted.
  explicit RecordingSurvey(int nq, bool keep_intervals = true);
  void add(double t, const std::uint8_t* given);  // a row as RecordingBuilder's sink gives it
  // 5 x the median interval: default_max_gap of the stamps, without holding them.
  double default_max_gap() const;
  // Every coordinate's positions in every row or in none: OfflineStream computes it.
  bool streamable() const;

  int nq;
  bool keep_intervals;
  long rows = 0;
  std::vector<char> position_everywhere, position_somewhere, velocity_everywhere;
  std::map<double, long> intervals;  // t[i] - t[i - 1], counted
  double last_stamp = 0;
};

class OfflineStream {
 public:
  using RowSink = std::function<void(const OfflineRow&)>;
  // max_gap > 0 (the survey's default_max_gap unless the user gave one), velocity_everywhere
  // from the survey; `model`, `estimator` outlive this object. chunk_rows: rows computed at once.
  OfflineStream(const Model& model, const OfflineEstimator& estimator, const OfflineReach& reach,
                double max_gap, std::vector<char> velocity_everywhere, int threads, int chunk_rows,
                RowSink sink);

  // A row as RecordingBuilder's sink gives it; computes a chunk when its rows are ready.
  void add(double t, const double* position, const double* velocity, const std::uint8_t* given);
  // Computes the rows left.
  void finish();
  // Every chunk's OfflineBatch formats its rows with `f` (OfflineBatch::set_formatter).
  void set_formatter(OfflineBatch::Formatter f) { formatter_ = std::move(f); }

  int buffered_rows() const { return buffer_.rows(); }
  int peak_buffered_rows() const { return peak_rows_; }
  RowSeconds seconds() const { return seconds_; }
  int threads() const { return threads_; }

 private:
  int ready_end() const;  // rows [next_, ready_end()) can be computed now
  void compute(int end);  // rows [next_, end) of the buffer, then forgets what is behind
  void forget();          // drops rows no estimate still to compute reaches

  const Model& model_;
  const OfflineEstimator& estimator_;
  OfflineReach reach_;
  double max_gap_;
  std::vector<char> velocity_everywhere_;
  int threads_, chunk_rows_;
  RowSink sink_;
  OfflineBatch::Formatter formatter_;
  Recording buffer_;  // the rows kept, oldest first
  int next_ = 0;      // buffer row of the first row not yet computed
  int peak_rows_ = 0;
  RowSeconds seconds_;
};

}  // namespace mbk
