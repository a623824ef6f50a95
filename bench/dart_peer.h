// DART (Debian's libdart-dev) in kinematics_benchmark (only when CMake finds it).
#pragma once

#include "bench/bench_scene.h"

namespace mbk_bench {

// Registers dart/<scene>/full: set q, q', q'' and read every body's world transform, angular
// velocity and acceleration, and mass-center position, velocity and acceleration (DART computes
// them lazily on these reads), after checking that DART and we agree on every body.
void register_dart(const Scene& scene);

}  // namespace mbk_bench
