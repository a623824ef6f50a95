// Joint velocities and accelerations estimated from a position-only stream (a
// sensor_msgs/JointState without them): error against the exact derivatives, run time and
// latency of every estimator on the demo's known trajectories (demo_trajectory.h) at 100 Hz
// and 1 kHz, with and without timestamp jitter, with position noise 0, 1e-6 and 1e-4 rad.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/analysis/demo_trajectory.h"
#include "mb_kinematics/estimation/auto_estimator.h"

namespace mbk {

struct EstimatorResult {
  std::string method;                // estimator name, as ~acceleration_estimator takes it
  std::string stream;                // e.g. "1000Hz jitter20% noise1e-06"
  double median_ns, min_ns, max_ns;  // per sample and coordinate (add + estimate)
  double error;      // largest |x'' - exact| over coordinates and samples (after a 1 s warm-up),
                     // divided by the largest |exact x''| over them
  std::string note;  // velocity error (the same way) and latency in samples
};

// Every estimator of derivative_estimator_names() (the node's) and of offline_estimator_names()
// (mbk bag's, note "offline"; also with noise 1e-3 and 1e-2) on every stream of `waves` (one
// estimator per coordinate, each wave sampled at the same stamps).
std::vector<EstimatorResult> estimator_study(const std::vector<Wave>& waves, bool quick);

// A human-like recording: the demo's waves (demo_waves) with frequencies spread over 0.2 to
// 5 Hz (log-spaced by the golden ratio), amplitudes falling as 1/f above 1 Hz (the demo's
// 0.4 rad, 0.05 m, 0.2 below).
std::vector<Wave> human_like_waves(const Model& model);

// A study stream's stamps t and noisy samples x[i * m + c]: `rate` Hz over `seconds`, stamps
// jittered uniformly by +-jitter/rate, Gaussian position noise of standard deviation `noise` (the
// same stamps for any noise; the same noise for any waves of the same count).
void study_stream(const std::vector<Wave>& waves, double rate, double jitter, double noise,
                 double seconds, std::vector<double>& t, std::vector<double>& x);

// One stream: samples at `rate` Hz over `seconds`, stamps jittered uniformly by +-jitter/rate
// (exact stamps), Gaussian position noise of standard deviation `noise`; the run time is the
// median over `repetitions`.
EstimatorResult run_estimator(const std::string& name, const std::vector<Wave>& waves, double rate,
                              double jitter, double noise, double seconds, int repetitions);

// The same stream through an offline estimator (estimation/offline_estimator.h) as mbk bag runs it:
// weights once per sample for all coordinates; the error over every sample, the recording's
// ends included (no warm-up); the run time per sample and coordinate includes the weights.
EstimatorResult run_offline_estimator(const std::string& name, const std::vector<Wave>& waves,
                                      double rate, double jitter, double noise, double seconds,
                                      int repetitions);

// An offline estimator's errors on one stream, each the largest |estimate - exact| over the
// coordinates and samples divided by the largest |exact| (velocity, acceleration): over every
// sample, and away from the ends (0.5 s).
struct OfflineAccuracy {
  double velocity = 0, acceleration = 0, velocity_inside = 0, acceleration_inside = 0;
};
OfflineAccuracy offline_accuracy(const std::string& name, const std::vector<Wave>& waves,
                                 double rate, double jitter, double noise, double seconds);
// The same of the estimates a.first, a.second ([i * m + c]) at the stamps t.
OfflineAccuracy offline_accuracy(const std::vector<Wave>& waves, const std::vector<double>& t,
                                 const AutoEstimate& a);

}  // namespace mbk
