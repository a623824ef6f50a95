// STATE.json for `mbk eval`: {"position": {coord: value}, "velocity": {...},
// "acceleration": {...}} (doc/method.md 8). Missing coordinates are 0, except that a missing Euler
// parameter set is the identity (e4 = 1). Mimic coordinates are computed from their sources.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

// The state when none is given, as an empty STATE.json reads: coordinates 0 (an Euler parameter
// set the identity), mimic coordinates from their sources (multiplier * 0 + offset).
JointState<double> default_state(const Model& model);

// Throws std::invalid_argument naming the file and the bad key or value.
JointState<double> read_state_string(const Model& model, const std::string& text,
                                     const std::string& source = "<state>");
// PATH "-" reads standard input.
JointState<double> read_state_file(const Model& model, const std::string& path);

}  // namespace mbk
