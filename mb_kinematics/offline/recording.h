// Recorded joint samples (from a bag or a trajectory CSV) in one table, ready for the offline
// kinematics: one row per accepted sample, positions (and velocities, accelerations where the
// recording gives them) of every coordinate of a model. Everything rejected is counted by
// reason; nothing is lost silently. ROS-free.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mb_kinematics/core/joint_state_intake.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/estimation/stamp_grid.h"

namespace mbk {

// Counted drops (samples not written) and notes (samples written, something ignored), by
// reason; `example` keeps the first message of each reason.
struct DropLog {
  std::map<std::string, long> drops, notes;
  std::map<std::string, std::string> example;
  void drop(const std::string& reason, const std::string& detail);
  void note(const std::string& reason, const std::string& detail);
  long dropped() const;
};

struct Recording {
  int nq = 0;
  std::vector<double> stamp;         // seconds, increasing
  std::vector<double> position;      // rows x nq, row-major
  std::vector<double> velocity;      // rows x nq, where kVelocity is set
  std::vector<double> acceleration;  // rows x nq, where kAcceleration is set
  std::vector<std::uint8_t> given;   // rows x nq: kPosition | kVelocity | kAcceleration
  // The stamps' uniform grid, when they are on one (estimation/stamp_grid.h). When it moves
  // them, `stamp` holds the grid's times (for the derivatives) and `recorded_stamp` the stamps
  // as recorded (the outputs' times); else recorded_stamp is empty.
  StampGrid grid;
  std::vector<double> recorded_stamp;
  double stamp_rounding = 0;  // the stamps' own (a CSV's decimals), 0: a bag's nanoseconds
  // Whole seconds every stamp above is counted from (a trajectory CSV's first: a wall-clock time
  // keeps its nanoseconds, which a double of 1.7e9 s does not); the time is origin + stamp.
  double origin = 0;
  static constexpr std::uint8_t kPosition = 1, kVelocity = 2, kAcceleration = 4;
  int rows() const { return static_cast<int>(stamp.size()); }
  double recorded(int r) const { return recorded_stamp.empty() ? stamp[r] : recorded_stamp[r]; }
  // Moves the stamps onto their grid when they lie on one (recorded_stamp keeps them).
  void snap_to_grid();
};

// Builds a Recording from samples by coordinate name, as the node merges joint_states:
// unknown names are ignored (noted), a coordinate a sample does not name keeps its last value
// (the derivatives of that coordinate come from its own samples), mimic coordinates are
// computed later. Dropped (counted): unequal lengths, a name given twice, NaN/Inf, a stamp
// before the previous sample's or equal to it, samples before every coordinate has been named
// once. Euler parameters that flip sign (e and -e) are kept continuous. A position that is a
// gross outlier of its coordinate's series (estimation/outliers.h) is noted and excluded: that
// coordinate is not given in that row (its derivatives come from its other samples) and its
// value there is its window's median. Rows leave a few samples late for that test (finish()
// sends the last ones).
class RecordingBuilder {
 public:
  explicit RecordingBuilder(const Model& model);

  // One sample at t: names[i] has position[i] and, if velocity is non-empty, velocity[i].
  // `where` names the sample in messages (e.g. "message 12 at t = 3.25").
  void add(double t, const std::vector<std::string>& names, const std::vector<double>& position,
           const std::vector<double>& velocity, const std::string& where);
  // Accelerations for the sample of the same stamp (added before or after it).
  void add_accelerations(double t, const std::vector<std::string>& names,
                         const std::vector<double>& acceleration, const std::string& where);

  // Streaming: every accepted row goes to `sink` as it is added instead of into the table, and
  // rows before every coordinate was named are dropped then (the same drops as finish()'s).
  // Set before the first add; joint_accelerations need the table (add_accelerations refuses).
  using RowSink = std::function<void(double t, const double* position, const double* velocity,
                                     const std::uint8_t* given)>;
  void stream_to(RowSink sink) { sink_ = std::move(sink); }
  // Every later add() at t + seconds (mbk bag --start-time); set before the first add.
  void offset_times(double seconds) { time_offset_ = seconds; }
  // A stamp read from text, off its true time by up to about `rounding` seconds (from its last
  // decimal): the stamps' grid allows the finest such rounding noted (Recording::stamp_rounding).
  void note_stamp_rounding(double rounding) {
    if (stamp_rounding_ == 0 || rounding < stamp_rounding_) stamp_rounding_ = rounding;
  }
  double stamp_rounding() const { return stamp_rounding_; }
  // The whole seconds the reader counts the stamps it adds from (Recording::origin); set before
  // the first add.
  void set_time_origin(double seconds) { origin_ = seconds, has_origin_ = true; }
  bool has_time_origin() const { return has_origin_; }
  double time_origin() const { return origin_; }

  // The table; rows before every coordinate was named are dropped here ("missing joints").
  // Stamps on a uniform grid to within their rounding are moved to the grid's times
  // (Recording::snap_to_grid).
  // Streaming: checks that every coordinate was named and returns an empty table.
  Recording finish();
  DropLog& log() { return log_; }
  long samples_read() const { return read_; }

 private:
  // A row held until the outlier test has seen the samples after it.
  struct PendingRow {
    double t;
    std::vector<double> row, vrow;
    std::vector<std::uint8_t> given;
    std::string where;
  };
  void hold(PendingRow pending);
  PendingRow spare_row();     // one emitted before, its buffers reused (else a new one)
  void test_outliers(int p);  // pending_[p] against the pending rows around it
  void exclude_outlier(int p, int c, double median, double scale);
  void release_pending();  // the rows held at the end
  void emit(const PendingRow& r);
  std::vector<std::string> not_named_yet() const;

  const Model& model_;
  JointStateIntake intake_;  // the samples' names, checks and Euler signs; the last positions
  CoordinateLookup acceleration_names_;
  std::vector<char> mimic_;
  Recording rec_;
  std::map<double, std::pair<std::vector<double>, std::vector<char>>> accelerations_;
  DropLog log_;
  long read_ = 0;
  RowSink sink_;
  bool has_last_stamp_ = false;
  double last_stamp_ = 0;  // of the last row accepted
  double time_offset_ = 0;
  std::deque<PendingRow> pending_;
  std::vector<PendingRow> spare_;  // emitted rows, for their buffers (no allocation per row)
  bool tested_head_ = false;  // the first rows held have been tested
  double stamp_rounding_ = 0;  // 0: none noted
  double origin_ = 0;
  bool has_origin_ = false;
};

}  // namespace mbk
