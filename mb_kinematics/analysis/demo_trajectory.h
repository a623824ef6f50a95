// The demo's smooth, known joint trajectories: every coordinate i follows
// q_i(t) = b_i + a_i sin(w_i t + p_i). demo_publisher streams them (with exact velocities and
// accelerations); the work-precision report samples the same ones to study the estimators.
#pragma once

#include <vector>

#include "mb_kinematics/core/model.h"

namespace mbk {

struct Wave {
  double b = 0, a = 0, w = 0, p = 0;
  // The value (order 0) or its first or second time derivative at time t.
  double at(double t, int order) const;
};

// One wave per coordinate (mimic coordinates included; callers skip them): amplitudes 0.05 m
// for translations, 0.4 rad for angles, 0.2 about the identity for Euler parameters (e4 = 1 +
// ...); frequencies spread over 0.2 to 0.6 Hz by the golden ratio; phases 0.7 i.
std::vector<Wave> demo_waves(const Model& model);

}  // namespace mbk
