// Pinocchio 3.x in kinematics_benchmark (only when CMake finds it: bench/bench.cmake).
#pragma once

#include "bench/bench_scene.h"

namespace mbk_bench {

// Registers pinocchio/<scene>/pose (forwardKinematics(q)) and pinocchio/<scene>/full
// (forwardKinematics(q, v, a) and every body's mass-center position, velocity and acceleration,
// omega and alpha in world components: our full state), after checking that Pinocchio and we
// agree on every body. Angles of continuous joints go to Pinocchio's (cos, sin) inside the loop.
void register_pinocchio(const Scene& scene);

}  // namespace mbk_bench
