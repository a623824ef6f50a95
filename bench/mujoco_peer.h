// MuJoCo 2.2.2 (Debian's libmujoco-dev) in kinematics_benchmark (only when CMake finds it).
#pragma once

#include "bench/bench_scene.h"

namespace mbk_bench {

// Registers mujoco/<scene>/pose (mj_kinematics) and mujoco/<scene>/full (mj_kinematics,
// mj_comPos, mj_comVel, mj_rnePostConstraint with gravity off, then every body's velocity and
// acceleration at its mass center, mj_objectVelocity and mj_objectAcceleration, as ours gives
// them), on MuJoCo's own qpos, qvel, qacc, after checking that MuJoCo and we agree on every
// body. MuJoCo reads the scene's URDF (scene.urdf, its fixed links kept: fusestatic off,
// massless links bounded to 1e-6 kg) or its MJCF file (scene.mjcf).
void register_mujoco(const Scene& scene);

}  // namespace mbk_bench
