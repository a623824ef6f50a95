// MuJoCo's state (qpos, qvel, qacc) as ours, for the MuJoCo peer test and benchmark: coordinates
// by name (hinge and slide: the joint's name; ball: <joint>/e1..e4 from qpos (w, x, y, z) as
// e4 = w; free: <joint>/x, y, z, then e1..e4), the Euler-parameter rates from MuJoCo's local
// angular velocity w and its rate: e' = e (0, w) / 2, e'' = (e' (0, w) + e (0, w')) / 2
// (quaternion products). Mimic coordinates come from our mimics. An unnamed joint is joint<id>,
// as ours names it.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk_test {

// A random state of MuJoCo's: angles and translations in [-pi, pi], unit quaternions, speeds in
// [-2, 2], accelerations in [-5, 5]; linear joint equalities hold.
inline void random_mujoco_state(const mjModel* m, mjData* d, std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), speed(-2, 2), rate(-5, 5);
  std::normal_distribution<double> normal;
  for (int i = 0; i < m->nq; ++i) d->qpos[i] = angle(rng);
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = speed(rng), d->qacc[i] = rate(rng);
  for (int j = 0; j < m->njnt; ++j) {
    const int t = m->jnt_type[j];
    if (t != mjJNT_BALL && t != mjJNT_FREE) continue;
    mjtNum* q = d->qpos + m->jnt_qposadr[j] + (t == mjJNT_FREE ? 3 : 0);
    Eigen::Vector4d e(normal(rng), normal(rng), normal(rng), normal(rng));
    e.normalize();
    for (int i = 0; i < 4; ++i) q[i] = e[i];
  }
  for (int e = 0; e < m->neq; ++e) {
    if (m->eq_type[e] != mjEQ_JOINT || m->eq_obj2id[e] < 0) continue;
    const mjtNum* c = m->eq_data + mjNEQDATA * e;
    const int q1 = m->jnt_qposadr[m->eq_obj1id[e]], q2 = m->jnt_qposadr[m->eq_obj2id[e]];
    const int v1 = m->jnt_dofadr[m->eq_obj1id[e]], v2 = m->jnt_dofadr[m->eq_obj2id[e]];
    d->qpos[q1] = m->qpos0[q1] + c[0] + c[1] * (d->qpos[q2] - m->qpos0[q2]);
    d->qvel[v1] = c[1] * d->qvel[v2];
    d->qacc[v1] = c[1] * d->qacc[v2];
  }
}

// Euler parameters (e1, e2, e3, e4), their rates and second rates from MuJoCo's quaternion
// (w, x, y, z) and local angular velocity and acceleration.
inline void euler_parameters(const mjtNum* quat, const mjtNum* w, const mjtNum* wd, double* q,
                             double* qd, double* qdd) {
  const Eigen::Quaterniond e(quat[0], quat[1], quat[2], quat[3]), wq(0, w[0], w[1], w[2]),
      wdq(0, wd[0], wd[1], wd[2]);
  const Eigen::Quaterniond ed(0.5 * (e * wq).coeffs());
  const Eigen::Quaterniond edd(0.5 * ((ed * wq).coeffs() + (e * wdq).coeffs()));
  for (int i = 0; i < 4; ++i)  // Eigen's coeffs(): x, y, z, w
    q[i] = e.coeffs()[i], qd[i] = ed.coeffs()[i], qdd[i] = edd.coeffs()[i];
}

// Our coordinate `name`; throws std::runtime_error naming it when the model has none.
inline int mujoco_coordinate(const mbk::Model& model, const std::string& name) {
  const int i = model.coordinate_index(name);
  if (i < 0) throw std::runtime_error("MuJoCo's coordinate " + name + " is no coordinate of ours");
  return i;
}

// MuJoCo's joint j by the name ours gives it (doc/conventions.md: unnamed, joint<j>).
inline std::string joint_name(const mjModel* m, int j) {
  const char* name = m->names + m->name_jntadr[j];
  return *name ? std::string(name) : "joint" + std::to_string(j);
}

inline mbk::JointState<double> our_state(const mjModel* m, const mjData* d,
                                         const mbk::Model& model) {
  mbk::JointState<double> state(model);
  std::vector<bool> mimic(model.nq, false);
  for (const mbk::Mimic& x : model.mimics) mimic[x.coordinate] = true;
  for (int j = 0; j < m->njnt; ++j) {
    const std::string name = joint_name(m, j);
    const mjtNum* q = d->qpos + m->jnt_qposadr[j];
    const mjtNum* v = d->qvel + m->jnt_dofadr[j];
    const mjtNum* a = d->qacc + m->jnt_dofadr[j];
    const int t = m->jnt_type[j];
    if (t == mjJNT_HINGE || t == mjJNT_SLIDE) {
      const int i = mujoco_coordinate(model, name);
      if (mimic[i]) continue;
      state.position[i] = q[0], state.velocity[i] = v[0], state.acceleration[i] = a[0];
      continue;
    }
    int i = 0;
    if (t == mjJNT_FREE) {
      for (const char* c : {"x", "y", "z"}) {
        const int k = mujoco_coordinate(model, name + "/" + c);
        state.position[k] = q[i], state.velocity[k] = v[i], state.acceleration[k] = a[i];
        ++i;
      }
    }
    double e[4], ed[4], edd[4];
    euler_parameters(q + i, v + i, a + i, e, ed, edd);
    for (int c = 0; c < 4; ++c) {
      const int k = mujoco_coordinate(model, name + "/e" + std::to_string(c + 1));
      state.position[k] = e[c], state.velocity[k] = ed[c], state.acceleration[k] = edd[c];
    }
  }
  mbk::apply_mimics(model, state);
  return state;
}

}  // namespace mbk_test
