// Which bodies the coordinates known so far place (the node's ~missing_coordinates):
// body k is known iff every coordinate of its joint and of every joint on its chain to R is
// known, the chain k, L(k), L^2(k), ..., 0 of the lower body array (doc/method.md 1, eq. 4.2.1).
// A mimic coordinate is known iff its source is (q = m q_source + c).
#pragma once

#include <vector>

#include "mb_kinematics/core/model.h"

namespace mbk {

// `coordinate_known`: model.nq entries, 1 where the coordinate is known; its mimic entries are
// overwritten from their sources (model.mimics is in dependency order). Fills `body_known`
// (N + 1 entries; [0], R, is always known) and returns the number of known bodies. Allocates
// only when `body_known` has the wrong size.
int known_bodies(const Model& model, std::vector<char>& coordinate_known,
                 std::vector<char>& body_known);

}  // namespace mbk
