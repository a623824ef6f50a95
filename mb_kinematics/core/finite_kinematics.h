// Whether forward_kinematics' results are finite: the node and mbk bag drop a sample whose
// kinematics is not (doc/stability.md) rather than publish NaN or Inf. ROS-free.
#pragma once

#include "mb_kinematics/core/data.h"

namespace mbk {

// Every number of bodies 1..N that `level` computes (rotation, origin and mass center; with
// velocities omega and both velocities; with accelerations alpha and both accelerations) is
// finite: one vectorized pass per array, no branch per number.
bool finite_kinematics(const Data<double>& data, Level level);

// The same for body k alone (to name the first body that is not finite).
bool finite_kinematics(const Data<double>& data, int k, Level level);

}  // namespace mbk
