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
#include <memory>
#include <vector>

#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/exact_median.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace mbk {

// What the computation of a whole recording depends on beyond one estimate's reach, gathered
// row by row in passes over the input, in memory bounded independently of its length: the first
// pass sees every row (add); the median interval between stamps (which sets max_gap) is exact
// after one pass at a steady rate, and after one more of the stamps alone (add_stamp) for
// jittered stamps of every distinct interval (estimation/exact_median.h).
struct RecordingSurvey {
  // keep_intervals false: the user gave max_gap; the intervals are not counted. interval_bins:
  // ExactMedian's bound (about 48 bytes each).
  explicit RecordingSurvey(int nq, bool keep_intervals = true, std::size_t interval_bins = 1 << 14);
  void add(double t, const std::uint8_t* given);  // a row as RecordingBuilder's sink gives it
  // Ends a pass: true when default_max_gap() is known; false when every stamp is needed once more
  // (add_stamp each, then finish_pass()).
  bool finish_pass();
  void add_stamp(double t);  // a pass after the first
  // 5 x the median interval: default_max_gap of the stamps, without holding them.
  double default_max_gap() const;
  // Every coordinate's positions in every row or in none: OfflineStream computes it.
  bool streamable() const;

  int nq;
  bool keep_intervals;
  long rows = 0;
  std::vector<char> position_everywhere, position_somewhere, velocity_everywhere;
  ExactMedian intervals;  // t[i] - t[i - 1]
  long stamps_in_pass = 0;
  double last_stamp = 0;
};

class OfflineStream {
 public:
  using RowSink = std::function<void(const OfflineRow&)>;
  // max_gap > 0 (the survey's default_max_gap unless the user gave one), `whole`: the survey's
  // velocity_everywhere ("auto": and AutoChoosePass's choices, `reach` theirs); `model`,
  // `estimator` outlive this object. chunk_rows: rows computed at once.
  OfflineStream(const Model& model, const OfflineEstimator& estimator, const OfflineReach& reach,
                double max_gap, WholeRecording whole, int threads, int chunk_rows, RowSink sink);

  // A row as RecordingBuilder's sink gives it; computes a chunk when its rows are ready.
  void add(double t, const double* position, const double* velocity, const std::uint8_t* given);
  // The stamps' grid (estimation/stamp_grid.h, found over the whole recording in passes before):
  // when it moves them, the rows are differentiated at the grid's times and keep their stamps
  // (Recording::recorded_stamp). Set before the first add.
  void set_stamp_grid(const StampGrid& grid) { grid_ = buffer_.grid = grid; }
  // The whole seconds the stamps added are counted from (Recording::origin), for messages.
  void set_time_origin(double seconds) { buffer_.origin = seconds; }
  // Computes the rows left.
  void finish();
  // Every chunk's OfflineBatch formats its rows with `f` (OfflineBatch::set_formatter).
  void set_formatter(OfflineBatch::Formatter f) { formatter_ = std::move(f); }
  // "auto": rows carry their bodies' error bars (OfflineBatch::set_body_errors).
  void set_body_errors(bool on) { body_errors_ = on; }
  // Called after each chunk with its states and rows [begin, end) of `piece`.
  using ChunkHook = std::function<void(const OfflineStates&, const Recording& piece, int, int)>;
  void set_chunk_hook(ChunkHook hook) { hook_ = std::move(hook); }
  // "auto": the whole recording's error bars (OfflineStates::error_summary), after finish().
  const std::vector<CoordinateError>& error_summary() const { return errors_; }

  // "auto": the bytes kept for error_summary's medians (bounded: ErrorColumns).
  std::size_t error_bytes() const { return columns_.bytes(); }
  int buffered_rows() const { return buffer_.rows(); }
  int peak_buffered_rows() const { return peak_rows_; }
  RowSeconds seconds() const { return seconds_; }
  int threads() const { return threads_; }

 private:
  int ready_end() const;  // rows [next_, ready_end()) can be computed now
  // Rows [next_, end) of the buffer, then forgets what is behind; last: the recording's end.
  void compute(int end, bool last = false);
  void forget();  // drops rows no estimate still to compute reaches

  const Model& model_;
  const OfflineEstimator& estimator_;
  OfflineReach reach_;
  double max_gap_;
  WholeRecording whole_;
  int threads_, chunk_rows_;
  RowSink sink_;
  OfflineBatch::Formatter formatter_;
  bool body_errors_ = false;
  ChunkHook hook_;
  StampGrid grid_;
  ErrorColumns columns_;  // "auto": every row's, for the medians of error_summary
  std::vector<CoordinateError> errors_;
  Recording buffer_;  // the rows kept, oldest first
  RowBlocks rows_;    // the chunks' results, made once
  int next_ = 0;      // buffer row of the first row not yet computed
  int peak_rows_ = 0;
  RowSeconds seconds_;
};

// "auto"'s choice pass (estimation/auto_estimator.h) over a recording given a row at a time after
// the survey, keeping only the rows a selection sample still to add reaches: the whole
// recording's choices for its positions and, where some coordinate has them in every row, for
// its given velocities, the same as estimate_auto's on the whole recording.
class AutoChoosePass {
 public:
  // threads: AutoChooser's. Also sums the rotation noise of the model's joints on angles
  // (offline/rotation_noise.h); `model` must outlive this object.
  AutoChoosePass(const Model& model, const RecordingSurvey& survey, double max_gap, int chunk_rows,
                 int threads = 1);
  void add(double t, const double* position, const double* velocity);
  // The stamps' grid (estimation/stamp_grid.h; the stamps added are its times where it moves
  // them): the windows' offsets are whole periods, as the estimating pass's. Before the first add.
  void set_stamp_grid(const StampGrid& grid) { grid_ = grid; }
  // The choices (with the survey's velocity_everywhere), and the estimating pass's reach: the
  // longest window chosen.
  WholeRecording finish(OfflineReach& reach);
  int peak_buffered_rows() const { return peak_rows_; }

 private:
  void take(int end);  // the selection samples among buffer rows [next_, end), then forgets

  int nq_;
  double max_gap_;
  int chunk_rows_;
  std::vector<char> velocity_everywhere_;
  AutoChooser positions_;
  std::unique_ptr<AutoChooser> velocities_;  // when some coordinate has them in every row
  OfflineReach reach_;                       // the longest candidate's
  RotationNoise rotations_;
  StampGrid grid_;
  std::vector<double> t_, position_, velocity_;  // the rows kept, oldest first
  long first_ = 0;                               // the recording's row of buffer row 0
  int next_ = 0, peak_rows_ = 0;
};

}  // namespace mbk
