#include "mb_kinematics/offline/bvh_recording.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace mbk {

// The outputs' stamps hold nanoseconds (a bag's ros::Time, the CSV's %.9f): frames closer than
// that would all get one stamp.
constexpr double kFinestFrameTime = 1e-9;

void add_bvh_frames(const BvhFile& bvh, const Model& model, double scale,
                    RecordingBuilder& builder) {
  if (!(scale > 0) || !std::isfinite(scale))  // as model_from_bvh's
    throw std::invalid_argument("scale: must be a positive number of metres per file unit");
  if (bvh.frame_time < kFinestFrameTime) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", bvh.frame_time);
    throw std::invalid_argument(bvh.path + ": Frame Time " + text +
                                " s is below 1 ns, finer than a stamp holds: correct the file's "
                                "Frame Time (seconds per frame, e.g. 0.008333 for 120 Hz)");
  }
  BvhFile unwrapped = bvh;
  unwrap_rotations(unwrapped);
  for (int f = 0; f < bvh.frame_count; ++f)
    builder.add((f + 1) * bvh.frame_time, model.coordinate_names,
                bvh_frame_coordinates(unwrapped, model, f, scale), {},
                "frame " + std::to_string(f));
}

JointState<double> bvh_frame_state(const BvhFile& bvh, const Model& model, double scale, int frame,
                                   const std::string& estimator) {
  bvh_frame_coordinates(bvh, model, frame, scale);  // throws for a frame the file lacks
  RecordingBuilder builder(model);
  add_bvh_frames(bvh, model, scale, builder);
  const Recording recording = builder.finish();
  const OfflineEstimator offline = make_offline_estimator(estimator);
  OfflineBatch batch(model, recording, offline, 0, nullptr, 1);
  std::vector<OfflineRow> row(1, OfflineRow(model));
  batch.compute(frame, frame + 1, row);
  if (!row[0].drop_reason.empty())
    throw std::invalid_argument(bvh.path + ": frame " + std::to_string(frame) + ": " +
                                row[0].drop_reason + " (" + row[0].drop_detail + ")");
  return row[0].state;
}

}  // namespace mbk
