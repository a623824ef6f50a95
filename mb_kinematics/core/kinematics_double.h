// kinematics.h with forward_kinematics in double compiled once, in mbk_core
// (kinematics_double.cc). Include this header, not kinematics.h, where the update runs in
// double: every file that instantiates the flattened loop itself (three levels and the AVX2
// copy) spends about 27 s of GCC's time at -O3 on it, nine tenths of a test file's compile.
// The call itself is the same function (one call through the shared library per update).
#pragma once

#include "mb_kinematics/core/kinematics.h"

namespace mbk {

extern template void forward_kinematics<double>(const Model&, const JointState<double>&,
                                                Data<double>&, Level);

namespace detail {

// The portable copy at each level, which a test runs beside the update chosen for the CPU
// (test/core/finite_difference_test.cc): compiled here too, not again there (11 CPU s).
extern template void forward_kinematics_at<Level::kPose, double, false>(const Model&,
                                                                        const JointState<double>&,
                                                                        Data<double>&);
extern template void forward_kinematics_at<Level::kVelocity, double, false>(
    const Model&, const JointState<double>&, Data<double>&);
extern template void forward_kinematics_at<Level::kAcceleration, double, false>(
    const Model&, const JointState<double>&, Data<double>&);

}  // namespace detail

}  // namespace mbk
