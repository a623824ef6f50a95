#include "mb_kinematics/offline/base_track.h"

#include <algorithm>
#include <utility>

#include "mb_kinematics/core/base_joint.h"
#include "mb_kinematics/core/point_kinematics.h"
#include "mb_kinematics/estimation/base_accelerations.h"
#include "mb_kinematics/offline/recording_states.h"

namespace mbk {

FloatingBaseTrack base_track(std::vector<BaseSample> samples, const OfflineEstimator& estimator,
                             double max_gap, const StampGrid& joints) {
  FloatingBaseTrack track;
  std::vector<double> t;
  for (const auto& b : samples) t.push_back(b.t);
  // Stamps on the joint states' grid take its times (the joint samples' times stay within the
  // odometry's span where they were); else those on a grid of their own take that grid's.
  if (!joints.moves || !std::all_of(t.begin(), t.end(), [&](double x) { return joints.holds(x); }))
    snap_to_stamp_grid(t);
  else
    for (double& x : t) x = joints.snap(x);
  for (size_t i = 0; i < t.size(); ++i) samples[i].t = t[i];
  std::vector<int> valid;
  base_accelerations(samples, estimator, max_gap > 0 ? max_gap : default_max_gap(t),
                     track.linear_acceleration, track.angular_acceleration, valid);
  track.samples = std::move(samples);
  return track;
}

void with_base_body(const Model& base_model, const Data<double>& data, Data<double>& out) {
  for (size_t k = 0; k < data.rotation.size(); ++k) {  // index 0: the root frame's motion
    out.rotation[k + 1] = data.rotation[k];
    out.origin[k + 1] = data.origin[k];
    out.omega[k + 1] = data.omega[k];
    out.alpha[k + 1] = data.alpha[k];
    out.origin_velocity[k + 1] = data.origin_velocity[k];
    out.origin_acceleration[k + 1] = data.origin_acceleration[k];
    out.mass_center[k + 1] = data.mass_center[k];
    out.mass_center_velocity[k + 1] = data.mass_center_velocity[k];
    out.mass_center_acceleration[k + 1] = data.mass_center_acceleration[k];
  }
  const PointMotion<Vec3<double>> g = body_point(out, 1, base_model.bodies[1].mass_center);
  out.mass_center[1] = g.position;
  out.mass_center_velocity[1] = g.velocity;
  out.mass_center_acceleration[1] = g.acceleration;
}

void recording_rows(const Model& model, const Recording& recording,
                    const OfflineEstimator& estimator, double max_gap,
                    const FloatingBaseTrack* base, int threads, DropLog& log,
                    const std::function<void(const OfflineRow&)>& keep) {
  require_coordinate_rates(model);
  OfflineBatch batch(model, recording, estimator, max_gap, base,
                     threads > 0 ? threads : default_thread_count());
  compute_rows(
      batch, model, 0, recording.rows(),
      [&](const OfflineRow& row) {
        if (!row.drop_reason.empty()) return log.drop(row.drop_reason, row.drop_detail);
        keep(row);
      },
      [](int) {});
}

FloatingBase floating_base(const Model& model, std::vector<BaseSample> samples,
                           const std::string& frame, const OfflineEstimator& estimator,
                           double max_gap, const StampGrid& joints) {
  return {base_track(std::move(samples), estimator, max_gap, joints),
          with_floating_base(model, frame, "base_odometry")};
}

BaseRows floating_base_rows(const Model& model, const Recording& recording,
                            std::vector<BaseSample> samples, const std::string& frame,
                            const OfflineEstimator& estimator, double max_gap, int threads,
                            DropLog& log) {
  const FloatingBase base =
      floating_base(model, std::move(samples), frame, estimator, max_gap, recording.grid);
  BaseRows out{base.layout, {}, {}, {}};
  recording_rows(
      model, recording, estimator, max_gap, &base.track, threads, log, [&](const OfflineRow& row) {
        out.stamp.push_back(row.stamp);
        out.data.emplace_back(out.layout);
        with_base_body(out.layout, row.data, out.data.back());
        out.system.emplace_back();
        system_kinematics(out.layout, out.data.back(), out.system.back(), Level::kAcceleration);
      });
  return out;
}

}  // namespace mbk
