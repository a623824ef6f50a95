// The partial velocity arrays of chosen bodies only (doc/method.md 5, 9), computed along their
// chains k, L(k), L^2(k), ... (doc/method.md 1): a request for the tip of a 10,000-link chain
// costs that chain's 10,000 columns, not the whole tree's O(N x depth) arrays
// (PartialVelocities: 50 million columns there). Same columns as independent_columns of the
// whole tree's arrays, to rounding.
#pragma once

#include <vector>

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

// Per body k (N + 1 entries, [0] for R is 0): the generalized speeds on its chain, i.e. the
// columns body k has before mimic folding (PartialVelocities::count). O(N).
std::vector<long> chain_speed_counts(const Model& model);

// For each body of `bodies` (indices 1..N, in that order), its independent columns
// (independent_columns: omega_kr, v_kr of G_k and their time derivatives, mimics folded) at
// `state` (q and y; y' is not used). Walks the union of the bodies' chains once: time and memory
// O(bodies on those chains + columns returned).
std::vector<std::vector<SpeedColumn>> chain_partial_velocities(const Model& model,
                                                               const JointState<double>& state,
                                                               const std::vector<int>& bodies);

}  // namespace mbk
