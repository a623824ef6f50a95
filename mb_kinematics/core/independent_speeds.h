// Partial velocities with respect to the independent generalized speeds: a mimic coordinate
// (q = m q_s + c, so y = m y_s) is not independent, and its column goes, times m, into its
// source's. Then omega_k = sum_r omega_kr y_r over the independent speeds r alone (doc/method.md
// 9).
#pragma once

#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/partial_velocity.h"

namespace mbk {

// Speed r's independent source and the factor y_r = factor * y_source (r itself and 1 unless r
// is a mimic coordinate; chains of mimics are followed).
int independent_speed(const Model& model, int r, double& factor);

// One column r of body k: omega_kr, v_kr (of G_k) and their time derivatives, in R.
struct SpeedColumn {
  int speed = 0;  // index of an independent generalized speed (model.speed_names)
  Vec3<double> omega, velocity, omega_dot, velocity_dot;
};

// Body k's nonzero columns (the speeds of its own chain), mimic columns folded into their
// sources', in the storage order of `pv` (from R outward). Allocates: not for the update loop.
std::vector<SpeedColumn> independent_columns(const Model& model,
                                             const PartialVelocities<double>& pv, int k);

}  // namespace mbk
