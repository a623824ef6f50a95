// Pinocchio 3.x in kinematics_benchmark (only when CMake finds it: bench/bench.cmake).
#pragma once

#include "bench/bench_scene.h"

namespace mbk_bench {

// Registers pinocchio/<scene>/pose (forwardKinematics(q)) and pinocchio/<scene>/full
// (forwardKinematics(q, v, a) and every body's mass-center position, velocity and acceleration,
// omega and alpha in world components: our full state), after checking that Pinocchio and we
// agree on every body. Our coordinates go to Pinocchio's inside the loop: (cos, sin) for
// continuous joints, quaternions and angular velocities in the child's frame for ball and free
// joints. pinocchio/<scene>/full_own_coordinates: the same full state from Pinocchio's own q, v
// and a (no conversion in the loop).
void register_pinocchio(const Scene& scene);

}  // namespace mbk_bench
