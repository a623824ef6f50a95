// A recording's floating base (mbk bag --base-odometry; the node's semantics,
// core/floating_base.h): the odometry with its accelerations from the offline estimator, and the
// rows' kinematics in the node's layout (with_floating_base: body 1 the base), as mbk bag writes
// them and the Python module's recording_kinematics returns them (doc/python.md). ROS-free.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/estimation/stamp_grid.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace mbk {

// The odometry samples (in time order) with their accelerations: the estimator's derivatives of
// the twist in R (max_gap 0: 5 x the median interval), differentiated at the joint states' grid
// times when every stamp lies on that grid (`joints`, Recording::grid), else on a grid of their
// own when they lie on one (estimation/stamp_grid.h); the samples take those times.
FloatingBaseTrack base_track(std::vector<BaseSample> samples, const OfflineEstimator& estimator,
                             double max_gap, const StampGrid& joints);

// A recording's floating base as mbk bag computes with it: the odometry's track (base_track)
// and the node's layout, with_floating_base(model, frame, "base_odometry") (`frame`: the
// odometry's frame_id, R).
struct FloatingBase {
  FloatingBaseTrack track;
  Model layout;
};
FloatingBase floating_base(const Model& model, std::vector<BaseSample> samples,
                           const std::string& frame, const OfflineEstimator& estimator,
                           double max_gap, const StampGrid& joints);

// The node's layout with ~base_odometry: `data` (of the model, carried into R by
// apply_floating_base) as `out` (of with_floating_base(model)): body 1 is the base, the root link
// on its free joint, with its mass center r_1 (p = O + S0K r, doc/method.md 3), the others follow.
void with_base_body(const Model& base_model, const Data<double>& data, Data<double>& out);

// mbk bag's rows of a whole recording, in memory: each row computed as mbk bag computes it
// (OfflineBatch: the estimator's states, mbk::check_state, the kinematics, with a floating base's
// `base` track or none) and handed to `keep` in order, or its drop counted in `log` as mbk bag
// counts it. threads: 0 for one per CPU.
void recording_rows(const Model& model, const Recording& recording,
                    const OfflineEstimator& estimator, double max_gap,
                    const FloatingBaseTrack* base, int threads, DropLog& log,
                    const std::function<void(const OfflineRow&)>& keep);

// Every row of `recording` whose kinematics mbk bag computes with this base (`frame`: the
// odometry's frame_id, R): the stamps, each row's Data in `layout`'s order, layout being
// with_floating_base(model, frame, "base_odometry"), and the whole system's (every link with mass,
// as the tidy CSV's system rows); the rows dropped are counted in `log`. threads: 0 for one per
// CPU.
struct BaseRows {
  Model layout;
  std::vector<double> stamp;
  std::vector<Data<double>> data;
  std::vector<SystemKinematics<double>> system;
};
BaseRows floating_base_rows(const Model& model, const Recording& recording,
                            std::vector<BaseSample> samples, const std::string& frame,
                            const OfflineEstimator& estimator, double max_gap, int threads,
                            DropLog& log);

}  // namespace mbk
