#include "bench/mujoco_peer.h"

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "test/support/mujoco_state.h"
#include "test/support/mujoco_urdf.h"

namespace mbk_bench {
namespace {

using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

struct MujocoRun {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::vector<int> body;                       // our Bk of MuJoCo's body b (R: 0, none: -1)
  std::vector<mjtNum> velocity, acceleration;  // 6 per body: rotational, then linear
  ~MujocoRun() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
};

mjModel* load(const Scene& scene) {
  char error[1000] = "";
  if (!scene.mjcf.empty()) return mj_loadXML(scene.mjcf.c_str(), nullptr, error, sizeof error);
  std::string message;
  mjModel* m = mbk_test::load_urdf_in_mujoco(scene.urdf, &message);
  if (!m) std::fprintf(stderr, "%s: MuJoCo refuses it: %s\n", scene.name.c_str(), message.c_str());
  return m;
}

std::unique_ptr<MujocoRun> make_run(const Scene& scene) {
  auto r = std::make_unique<MujocoRun>();
  r->m = load(scene);
  if (!r->m) std::exit(1);
  r->m->opt.gravity[0] = r->m->opt.gravity[1] = r->m->opt.gravity[2] = 0;
  r->d = mj_makeData(r->m);
  r->body.assign(r->m->nbody, 0);
  for (int b = 1; b < r->m->nbody; ++b) {
    const std::string name = r->m->names + r->m->name_bodyadr[b];
    r->body[b] = name == scene.model.bodies[0].name ? 0 : scene.model.body_index(name);
  }
  r->velocity.assign(6 * r->m->nbody, 0);
  r->acceleration.assign(6 * r->m->nbody, 0);
  std::mt19937 rng(1);
  mbk_test::random_mujoco_state(r->m, r->d, rng);
  return r;
}

void pose(MujocoRun& r) { mj_kinematics(r.m, r.d); }

void full(MujocoRun& r) {
  mj_kinematics(r.m, r.d);
  mj_comPos(r.m, r.d);
  mj_comVel(r.m, r.d);
  mj_rnePostConstraint(r.m, r.d);
  for (int b = 1; b < r.m->nbody; ++b) {
    mj_objectVelocity(r.m, r.d, mjOBJ_BODY, b, r.velocity.data() + 6 * b, 0);
    mj_objectAcceleration(r.m, r.d, mjOBJ_BODY, b, r.acceleration.data() + 6 * b, 0);
  }
}

// True when every MuJoCo body is one of ours and MuJoCo and we agree on each (frame, mass center,
// omega, alpha, the mass center's velocity and acceleration) to 1e-9 (disagreement); else says so.
bool check_agreement(const Scene& scene, MujocoRun& r) {
  const mbk::JointState<double> state = mbk_test::our_state(r.m, r.d, scene.model);
  mbk::Data<double> data(scene.model);
  mbk::forward_kinematics(scene.model, state, data);
  full(r);
  double e = 0;
  int bodies = 0;
  for (int b = 1; b < r.m->nbody; ++b) {
    const int k = r.body[b];
    if (k < 0) continue;
    ++bodies;
    if (k == 0) continue;  // a URDF's root link: ours is R, MuJoCo's a body welded to its world
    const auto vec = [](const mjtNum* v) { return Eigen::Vector3d(v[0], v[1], v[2]); };
    e = std::max(e, disagreement(vec(r.d->xpos + 3 * b), data.origin[k]));
    e = std::max(e, disagreement(Eigen::Map<const RowMat3>(r.d->xmat + 9 * b), data.rotation[k]));
    e = std::max(e, disagreement(vec(r.d->xipos + 3 * b), data.mass_center[k]));
    e = std::max(e, disagreement(vec(r.velocity.data() + 6 * b), data.omega[k]));
    e = std::max(e, disagreement(vec(r.velocity.data() + 6 * b + 3), data.mass_center_velocity[k]));
    e = std::max(e, disagreement(vec(r.acceleration.data() + 6 * b), data.alpha[k]));
    e = std::max(
        e, disagreement(vec(r.acceleration.data() + 6 * b + 3), data.mass_center_acceleration[k]));
  }
  if (e < 1e-9 && bodies == r.m->nbody - 1) return true;
  std::fprintf(stderr, "%s: MuJoCo and ours disagree (%g, %d of MuJoCo's %d bodies): not timed\n",
               scene.name.c_str(), e, bodies, r.m->nbody - 1);
  return false;
}

void register_one(const std::string& name, std::shared_ptr<MujocoRun> r, void (*run)(MujocoRun&)) {
  benchmark::RegisterBenchmark(name.c_str(), [r, run](benchmark::State& st) {
    int64_t i = 0;
    for (auto _ : st) {
      nudge(r->d->qpos, r->d->qvel, r->m->nq < r->m->nv ? r->m->nq : r->m->nv, i++);
      run(*r);
      benchmark::DoNotOptimize(r->d->xpos);
      benchmark::ClobberMemory();
    }
    st.counters["bodies"] = r->m->nbody - 1;
  });
}

}  // namespace

void register_mujoco(const Scene& scene) {
  std::shared_ptr<MujocoRun> r = make_run(scene);
  if (!check_agreement(scene, *r)) return;
  register_one("mujoco/" + scene.name + "/pose", r, pose);
  register_one("mujoco/" + scene.name + "/full", r, full);
}

}  // namespace mbk_bench
