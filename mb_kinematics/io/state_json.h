// STATE.json for `mbk eval`: {"position": {coord: value}, "velocity": {...},
// "acceleration": {...}} (doc/method.md 8). Missing coordinates are 0, except that a missing Euler
// parameter set is the identity (e4 = 1). Mimic coordinates are computed from their sources.
#pragma once

#include <cstddef>
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
// PATH "-" reads standard input. A text longer than state_text_bound(model) is refused as soon
// as that much is read.
JointState<double> read_state_file(const Model& model, const std::string& path);
// The most bytes a state of `model` is read up to: 1 MiB, and for each entry its three sections
// may hold (a coordinate's position, a speed's velocity and acceleration) 64 bytes and 6 per
// byte of its name (a name written in \u escapes).
std::size_t state_text_bound(const Model& model);

}  // namespace mbk
