// The joint state of every row of a Recording, for the offline kinematics (mbk bag): positions
// as recorded, velocities and accelerations as recorded where given, else from the zero-phase
// estimator (estimation/offline_estimator.h) over that coordinate's own samples: accelerations from
// the given velocities when a coordinate has them at every sample, else from the positions.
// ROS-free.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/rotation_errors.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/median_histogram.h"
#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/offline/recording.h"
#include "mb_kinematics/offline/rotation_noise.h"

namespace mbk {

// One coordinate's error bars from the "auto" estimator: its noise level and the median over
// its samples of the standard errors of its velocity and acceleration (rad, rad/s, rad/s^2 or m;
// the medians to a relative 2^-11, MedianHistogram).
struct CoordinateError {
  std::string name;
  double noise = 0, velocity_se = 0, acceleration_se = 0;
};

// Per coordinate in every row: the histograms of the standard errors error_summary takes the
// medians of (estimation/median_histogram.h: bounded however long the recording).
struct ErrorColumns {
  std::vector<MedianHistogram> velocity, acceleration;
  std::size_t bytes() const;  // what the histograms' bins take
};

// What a piece of a longer recording (offline/offline_stream.h) takes from the whole one.
struct WholeRecording {
  std::vector<char> velocity_everywhere;  // per coordinate: velocities given in every row
  // "auto": the whole recording's choices (AutoChooser) for the positions and, where some
  // coordinate has them in every row, the given velocities; null: chosen over the piece.
  std::shared_ptr<const AutoChoice> positions, velocities;
  // "auto": per joint on angles (angle_joints), the rotation noise of the whole recording
  // (offline/rotation_noise.h); null: over the piece.
  std::shared_ptr<const std::vector<Mat3<double>>> rotation_noise;
};

class OfflineStates {
 public:
  // `model` (coordinate-derivative speeds) and `recording` must outlive this object. max_gap:
  // seconds; 0 means default_max_gap of the stamps. When `recording` is a piece of a longer one
  // (offline/offline_stream.h), `whole` says what it takes from the whole recording. threads:
  // "auto"'s estimating pass's (estimate_chosen).
  OfflineStates(const Model& model, const Recording& recording, const OfflineEstimator& estimator,
                double max_gap, const WholeRecording* whole = nullptr, int threads = 1);

  // Fills `state` for row r; returns "" or why the row cannot be computed (too few samples
  // around it for the derivatives). Rows in increasing order, each at most once; rows may be
  // skipped (a worker of OfflineBatch takes its own runs of rows), with the same results.
  std::string state_at(int r, JointState<double>& state);

  double max_gap() const { return max_gap_; }
  // Every estimated coordinate's error bars ("auto" only; empty for the fixed estimators):
  // medians over this recording's rows, or over `whole`'s (a longer recording's, gathered piece
  // by piece with append_errors).
  std::vector<CoordinateError> error_summary(const ErrorColumns* whole = nullptr) const;
  // "auto": rows [begin, end)'s standard errors that error_summary takes the medians of; the
  // coordinates shared out among up to `threads` threads (each column takes its rows in order).
  void append_errors(int begin, int end, ErrorColumns& out, int threads = 1) const;
  // The standard errors of each body's alpha and mass-center acceleration at row r, in `state`
  // (from state_at; `data` its forward_kinematics at Level::kAcceleration), propagated from the
  // coordinates' (core/body_errors.h; given derivatives and mimic rules count as exact; a
  // coordinate estimated over its own samples has its last sample's); with "auto", a joint on
  // angles from its rotation's noise (angle_covariance, core/rotation_errors.h). False, with
  // nothing set, for a fixed estimator.
  // "auto": the standard errors of row r's joint velocities and accelerations into the
  // coordinates' places of velocity_se and acceleration_se (nq each; a coordinate set by a mimic
  // rule is left as it is); false, with nothing set, as for body_errors.
  bool coordinate_errors(int r, double* velocity_se, double* acceleration_se) const;
  bool body_errors(int r, const JointState<double>& state, const Data<double>& data,
                   std::vector<Vec3<double>>& alpha_se, std::vector<Vec3<double>>& acceleration_se);

 private:
  // The samples of coordinates that are not in every row.
  struct Series {
    std::vector<double> t;
    std::vector<int> row;
    Segments segments;
    size_t next = 0;  // first entry not yet reached
    double velocity = 0, acceleration = 0;
    int valid = 0;
    std::shared_ptr<const AutoEstimate> fit;  // "auto": per sample, of positions then velocities
  };
  void fit_automatic(int threads);
  void find_rotations();
  Mat9 angle_covariance(size_t g, int r);
  const Mat3<double>& angle_noise(size_t g, int j);
  const AutoSampleWeights& weights_at(int r, int k);
  void load_automatic(int r);
  void estimate_series(size_t i, size_t entry);
  void series_errors(size_t i, int r, double& velocity_se, double& acceleration_se) const;
  void fill_full(int r, JointState<double>& state, int& valid) const;
  void derivatives(const DerivativeWeights& w, const std::vector<int>* rows, int c, bool velocity,
                   double& first, double& second) const;

  const Model& model_;
  const Recording& rec_;
  OfflineEstimator estimator_;
  double max_gap_;
  std::vector<int> full_;     // coordinates given in every row (share the weights)
  std::vector<int> partial_;  // the others (mimics aside)
  std::vector<char> velocity_everywhere_;
  std::shared_ptr<const AutoChoice> positions_choice_, velocities_choice_;  // WholeRecording's
  std::vector<int> rule_until_;  // per coordinate: rows before it is recorded (mimics: rule)
  // Per row, over the coordinates of full_: none has a derivative given; all have both.
  std::vector<char> positions_only_, derivatives_given_;
  std::vector<Series> series_;  // per coordinate in partial_
  Segments segments_;
  DerivativeWeights weights_, series_weights_;  // of full_'s coordinates, of a Series
  bool any_velocity_everywhere_ = false;
  int fit_valid_ = 2;  // the least DerivativeWeights::valid of full_'s coordinates at this row
  // "auto": the estimates of every row of full_'s coordinates (shared by OfflineBatch's
  // workers), of the positions and of the given velocities.
  std::shared_ptr<const AutoEstimate> positions_fit_, velocities_fit_;
  Eigen::VectorXd first_, second_, velocity_first_;  // scratch, nq
  Eigen::VectorXd speed_se_, speed_dot_se_;          // body_errors' scratch, nq
  // "auto": the joints on angles whose three angles are estimated from positions in every row,
  // each with its rotation noise (offline/rotation_noise.h), carried as rotations by body_errors.
  std::vector<AngleJoint> rotations_;
  std::vector<Mat3<double>> rotation_noise_;
  std::shared_ptr<const std::vector<Mat3<double>>> whole_noise_;  // WholeRecording's
  // angle_covariance's scratch: per candidate window, its weights at row weights_row_[k].
  std::vector<AutoSampleWeights> window_weights_;
  std::vector<int> weights_row_;
  struct Entry {
    int row, slot;
    double weight;
  };
  std::vector<Entry> entries_;
  // angle_noise's: per joint of rotations_, F_j of row j at [j % noise_rows_], and that row
  // (-1: none).
  static constexpr size_t kAngleNoiseEntries = size_t{1} << 18;
  size_t noise_rows_ = 1;
  std::vector<Mat3<double>> noise_at_;
  std::vector<int> noise_row_;
  std::vector<Vec3<double>> alpha_var_, acceleration_var_;
  std::vector<char> subtree_;
  // body_errors' scratch, made at its first call; a copy (another worker's) starts without.
  struct Scratch {
    Scratch() = default;
    Scratch(const Scratch&) {}
    Scratch& operator=(const Scratch&) { return *this; }
    std::unique_ptr<PartialVelocities<double>> pv;
    std::unique_ptr<Data<double>> data;
  } scratch_;
};

}  // namespace mbk
