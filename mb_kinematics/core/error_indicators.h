// Cheap indicators of numerical trouble that a running node can report (doc/error_vs_runtime.md):
// each is O(N) or O(nq) and needs no reference computation.
#pragma once

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

// Largest ||S0K^T S0K - I|| (Frobenius) over bodies: rounding drift of the orientations, a few
// 1e-16 per level of depth in double; larger values mean bad input (e.g. non-unit axes).
double orthonormality_drift(const Data<double>& data);

// Largest | |e| - 1 | over the Euler-parameter joints of the state (0 if there are none): how
// far the input is from unit quaternions (the kinematics normalizes, but a large value points
// to a publisher's problem).
double euler_norm_error(const Model& model, const JointState<double>& state);

// Largest |q_i - (q0_i + v0_i dt + a0_i dt^2 / 2)| over coordinates: how well the previous
// sample's position, velocity and acceleration (given or estimated) predict the new positions
// dt seconds later. A consistent smooth stream gives O(|q'''| dt^3); noise, jumps or a poor
// estimator show up at once. Needs coordinate-derivative speeds (nq == nv).
double prediction_residual(const JointState<double>& previous, const JointState<double>& current,
                           double dt);

}  // namespace mbk
