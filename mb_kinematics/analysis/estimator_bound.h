// How well any local polynomial fit could do on a study stream (estimator_study.h): an oracle
// that knows the exact signal and the noise level picks, at each sample and for each coordinate,
// the least-squares polynomial (degree 2 to 6, any window length, every sample in it: no stride)
// whose expected squared acceleration error, bias^2 + sigma^2 |w''|^2, is the smallest (the bias
// from the exact signal at the window's stamps). The window is placed as the offline estimators
// place theirs (estimation/offline_estimator.h): centred where it can be, shifted to one side at
// the recording's ends. Its errors on the stream's own noise, and the smallest root-mean-square
// error a member of the family can have at the worst sample, bound what choosing the window and
// degree from the data ("auto") can reach on that stream.
#pragma once

#include <vector>

#include "mb_kinematics/analysis/demo_trajectory.h"

namespace mbk {

struct OracleBound {
  // The oracle's largest |x'' - exact| over the samples studied and the coordinates, divided by
  // the largest |exact x''| over every sample and coordinate (as offline_accuracy): within
  // `margin` s of the ends, and away from them (samples studied there: every `inside_stride`-th).
  double ends = 0, inside = 0;
  // The largest over the samples studied of the smallest root-mean-square error of the family at
  // that sample, min sqrt(bias^2 + sigma^2 |w''|^2), divided likewise: within `margin` of the
  // ends, and away from them.
  double ends_rms = 0, inside_rms = 0;
};

// The stream of offline_accuracy(name, waves, rate, jitter, noise, seconds) (the same stamps and
// noise). inside_stride <= 0: the ends only.
OracleBound local_polynomial_oracle(const std::vector<Wave>& waves, double rate, double jitter,
                                    double noise, double seconds, double margin, int inside_stride,
                                    bool phase_blind);

}  // namespace mbk
