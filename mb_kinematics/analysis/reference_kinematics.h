// The recursion in quad precision and in long double, the references of the error measures
// (kinematics_error.h, stability.h) and of the tests, compiled once in mbk_analysis
// (reference_kinematics_quad.cc, reference_kinematics_long_double.cc). Include this header, not
// core/kinematics.h, where the update runs in those types: GCC takes about 7 CPU s at -O3 for the
// loop in each (not flattened: kinematics.h), in every file that instantiates them.
#pragma once

#include "mb_kinematics/analysis/quad.h"
#include "mb_kinematics/core/kinematics_double.h"

namespace mbk {

extern template void forward_kinematics<Quad>(const Model&, const JointState<Quad>&, Data<Quad>&,
                                              Level);
extern template void forward_kinematics<long double>(const Model&, const JointState<long double>&,
                                                     Data<long double>&, Level);

}  // namespace mbk
