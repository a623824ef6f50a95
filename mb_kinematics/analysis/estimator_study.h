// Joint velocities and accelerations estimated from a position-only stream (a
// sensor_msgs/JointState without them): error against the exact derivatives, run time and
// latency of every estimator on known smooth trajectories at 100 Hz and 1 kHz, with and without
// timestamp jitter, with position noise 0, 1e-6 and 1e-4 rad.
#pragma once

#include <string>
#include <vector>

namespace mbk {

struct EstimatorResult {
  std::string method;                // estimator name, as ~acceleration_estimator takes it
  std::string stream;                // e.g. "1000Hz jitter20% noise1e-06"
  double median_ns, min_ns, max_ns;  // per sample and coordinate (add + estimate)
  double error;                      // max |x'' - exact| / max |exact x''| after warm-up
  std::string note;                  // velocity error and latency in samples
};

// The trajectory of the demo publisher: x(t) = 0.8 sin(2 pi 0.7 t + 0.3) + 0.3 sin(2 pi 2.3 t
// + 1.1) and its derivatives (order 0, 1, 2).
double demo_signal(double t, int order);

std::vector<EstimatorResult> estimator_study(bool quick);

// One stream: samples at `rate` Hz over `seconds`, stamps jittered uniformly by +-jitter/rate
// (exact stamps), Gaussian position noise of standard deviation `noise`.
EstimatorResult run_estimator(const std::string& name, double rate, double jitter, double noise,
                              double seconds, int repetitions);

}  // namespace mbk
