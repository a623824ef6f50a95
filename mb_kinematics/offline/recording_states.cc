#include "mb_kinematics/offline/recording_states.h"

#include <algorithm>
#include <stdexcept>

#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/bvh_recording.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/trajectory_csv.h"

namespace mbk {

Recording read_recording_file(const Model& model, const std::string& path, double bvh_scale,
                              DropLog& log) {
  RecordingBuilder builder(model);
  if (is_bvh_file(path))
    add_bvh_frames(read_bvh(path), model, bvh_scale, builder);
  else if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".csv") == 0)
    read_trajectory_csv(path, builder);
  else
    throw std::invalid_argument(path + ": not a recording this reads (.csv or .bvh)");
  Recording recording = builder.finish();
  log = builder.log();
  return recording;
}

Recording recording_of_positions(int nq, std::size_t rows, const double* time,
                                 const double* position) {
  Recording r;
  r.nq = nq;
  r.stamp.assign(time, time + rows);
  r.position.assign(position, position + rows * nq);
  r.velocity.assign(rows * nq, 0.0);
  r.acceleration.assign(rows * nq, 0.0);
  r.given.assign(rows * nq, Recording::kPosition);
  for (std::size_t i = 1; i < rows; ++i)
    if (!(time[i] > time[i - 1]))
      throw std::invalid_argument("times: not increasing at row " + std::to_string(i));
  r.snap_to_grid();  // as RecordingBuilder::finish
  return r;
}

void require_coordinate_rates(const Model& model) {
  if (model.speeds != SpeedKind::kCoordinateDerivatives)
    throw std::invalid_argument("a recording's states need speeds that are the coordinates' rates");
}

RecordingStates recording_states(const Model& model, const Recording& recording,
                                 const std::string& estimator, double max_gap) {
  require_coordinate_rates(model);
  OfflineStates states(model, recording, make_offline_estimator(estimator), max_gap);
  const std::size_t rows = recording.rows(), nq = model.nq;
  RecordingStates out;
  out.position.resize(rows * nq);
  out.velocity.resize(rows * nq);
  out.acceleration.resize(rows * nq);
  out.drop_reason.resize(rows);
  std::vector<double> vse(nq), ase(nq);
  bool errors = rows > 0;
  JointState<double> state(model);
  for (std::size_t r = 0; r < rows; ++r) {
    std::string& reason = out.drop_reason[r];
    reason = states.state_at(static_cast<int>(r), state);
    if (reason.empty()) {  // NaN from a denormal time step, as mbk bag drops the row
      const std::string problem = check_state(model, state);
      if (!problem.empty()) reason = "state rejected (mbk::check_state): " + problem;
    }
    std::copy(state.position.data(), state.position.data() + nq, &out.position[r * nq]);
    std::copy(state.velocity.data(), state.velocity.data() + nq, &out.velocity[r * nq]);
    std::copy(state.acceleration.data(), state.acceleration.data() + nq, &out.acceleration[r * nq]);
    std::fill(vse.begin(), vse.end(), 0.0);  // a mimic coordinate's: exact (its rule)
    std::fill(ase.begin(), ase.end(), 0.0);
    errors = errors && states.coordinate_errors(static_cast<int>(r), vse.data(), ase.data());
    if (errors) {
      out.velocity_se.insert(out.velocity_se.end(), vse.begin(), vse.end());
      out.acceleration_se.insert(out.acceleration_se.end(), ase.begin(), ase.end());
    }
  }
  if (!errors) out.velocity_se.clear(), out.acceleration_se.clear();
  return out;
}

}  // namespace mbk
