// A recording's joint states as `mbk bag` computes them, in memory (the Python module's
// read_recording and Model.states, doc/python.md): a trajectory CSV or a BVH file's motion read
// into a Recording as mbk bag reads it, and every row's velocities and accelerations from the
// offline estimator (OfflineStates), with their standard errors for "auto". ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk {

// `path`: a `.csv` trajectory (offline/trajectory_csv.h) or a `.bvh` file whose skeleton `model`
// is (model_from_bvh with the same `bvh_scale`). Samples merged and dropped as mbk bag does;
// `log` gets the counts. Throws std::invalid_argument naming the file and what is wrong.
Recording read_recording_file(const Model& model, const std::string& path, double bvh_scale,
                              DropLog& log);

// Positions (rows x nq, every coordinate in every row) at increasing times as a Recording (times
// on a uniform grid to within their rounding moved onto it, as RecordingBuilder::finish does);
// throws std::invalid_argument naming the first row whose time is not after the one before.
Recording recording_of_positions(int nq, std::size_t rows, const double* time,
                                 const double* position);

// Every row's state (rows x nq positions, rows x nv velocities and accelerations), the
// standard errors of the estimated velocities and accelerations (rows x nq; "auto" only, 0 where
// the recording gives the value; empty for the fixed estimators or when some coordinate is not
// in every row) and per row "" or why mbk bag drops it (too few samples around it).
struct RecordingStates {
  std::vector<double> position, velocity, acceleration;
  std::vector<double> velocity_se, acceleration_se;
  std::vector<std::string> drop_reason;
};

// Throws std::invalid_argument unless the model's speeds are its coordinates' rates (a
// recording's velocities are).
void require_coordinate_rates(const Model& model);

// `estimator`: as mbk bag --estimator ("auto", "centered_<N>_<order>", ...); max_gap: seconds,
// 0 for mbk bag's default. Throws std::invalid_argument for an unknown estimator or a model
// whose speeds are not the coordinates' derivatives.
RecordingStates recording_states(const Model& model, const Recording& recording,
                                 const std::string& estimator, double max_gap = 0);

}  // namespace mbk
