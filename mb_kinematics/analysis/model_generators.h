// Models and states made up for tests, benchmarks and reports: chains, random trees, the
// Euler-parameter variant of a model, random states.
#pragma once

#include <random>

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

// A chain of n bodies, each on a joint of `type` (revolute axes alternate z, y), links of
// length 1 along x, mass centers half way, unit masses.
Model make_chain(int n, JointType type);

// A random tree of n bodies: lower bodies mostly the previous body (deep chains), sometimes any
// earlier body (branches); joints of every type with random axes, offsets and C_k.
Model make_random_tree(int n, unsigned seed, SpeedKind speeds = SpeedKind::kCoordinateDerivatives);

// make_random_tree's shapes, axes, offsets and C_k with every joint revolute (n coordinates).
Model make_random_revolute_tree(int n, unsigned seed);

// The same model with every 1-2-3 angle joint replaced by its Euler-parameter twin
// (ball_123 -> ball_euler, free_123 -> free_euler), with the given speeds.
Model with_euler_parameters(const Model& model, SpeedKind speeds);

// The same model where every body without an inertia gets a random physical one about G_k
// (R diag(a, b, c) R^T, a and b in [0.1, 1], c between |a - b| and a + b, R random), for
// reports and tests of the system quantities; bodies with an inertia keep theirs.
Model with_random_inertias(Model model, unsigned seed);

// Uniform random positions in [-pi, pi] (Euler parameters: a random unit quaternion), speeds
// in [-1, 1] * speed_scale, accelerations in [-1, 1] * speed_scale^2.
JointState<double> random_state(const Model& model, std::mt19937& rng, double speed_scale = 1.0);

// Euler parameters of a rotation matrix (Shepperd's method), e4 >= 0.
template <typename S>
void quaternion_from_rotation(const Mat3<S>& r, S& e1, S& e2, S& e3, S& e4) {
  using std::sqrt;
  const S trace = r.trace();
  if (trace > S(0)) {
    const S s = S(2) * sqrt(trace + S(1));
    e4 = s / S(4), e1 = (r(2, 1) - r(1, 2)) / s, e2 = (r(0, 2) - r(2, 0)) / s;
    e3 = (r(1, 0) - r(0, 1)) / s;
  } else if (r(0, 0) > r(1, 1) && r(0, 0) > r(2, 2)) {
    const S s = S(2) * sqrt(S(1) + r(0, 0) - r(1, 1) - r(2, 2));
    e4 = (r(2, 1) - r(1, 2)) / s, e1 = s / S(4), e2 = (r(0, 1) + r(1, 0)) / s;
    e3 = (r(0, 2) + r(2, 0)) / s;
  } else if (r(1, 1) > r(2, 2)) {
    const S s = S(2) * sqrt(S(1) + r(1, 1) - r(0, 0) - r(2, 2));
    e4 = (r(0, 2) - r(2, 0)) / s, e1 = (r(0, 1) + r(1, 0)) / s, e2 = s / S(4);
    e3 = (r(1, 2) + r(2, 1)) / s;
  } else {
    const S s = S(2) * sqrt(S(1) + r(2, 2) - r(0, 0) - r(1, 1));
    e4 = (r(1, 0) - r(0, 1)) / s, e1 = (r(0, 2) + r(2, 0)) / s, e2 = (r(1, 2) + r(2, 1)) / s;
    e3 = s / S(4);
  }
  if (e4 < S(0)) e1 = -e1, e2 = -e2, e3 = -e3, e4 = -e4;
}

// The state of with_euler_parameters(model, speeds) that describes the same motion as `state`
// of `model`: e from the 1-2-3 rotation; with coordinate-derivative speeds
// e' = (e4 w + w x e) / 2, e4' = -(w . e) / 2 and their derivatives, where w and w' are the
// relative angular velocity and its derivative in the joint frame; with angular velocity
// speeds w and w' themselves. Computed in S (use a quad-precision S for a reference).
template <typename S>
JointState<S> euler_state(const Model& model, const Model& euler_model,
                          const JointState<S>& state) {
  JointState<S> out(euler_model);
  JointMotion<S> m;
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& from = model.bodies[k];
    const Body& to = euler_model.bodies[k];
    const int nq = coordinate_count(from.joint.type),
              nv = speed_count(to.joint.type, euler_model.speeds);
    const S* q = state.position.data() + from.q_index;
    const S* y = state.velocity.data() + from.v_index;
    const S* yd = state.acceleration.data() + from.v_index;
    if (!uses_euler_parameters(to.joint.type) ||
        (from.joint.type == to.joint.type && model.speeds == euler_model.speeds)) {
      for (int i = 0; i < nq; ++i) out.position[to.q_index + i] = q[i];
      for (int i = 0; i < nv; ++i) {
        out.velocity[to.v_index + i] = y[i];
        out.acceleration[to.v_index + i] = yd[i];
      }
      continue;
    }
    const int t = translation_count(from.joint.type);
    for (int i = 0; i < t; ++i) {
      out.position[to.q_index + i] = q[i];
      out.velocity[to.v_index + i] = y[i];
      out.acceleration[to.v_index + i] = yd[i];
    }
    Joint joint = from.joint;  // w, w' in the joint frame: the columns without C_k
    joint.rotation.setIdentity();
    joint_motion(joint, model.speeds, q, y, m);
    Vec3<S> w = Vec3<S>::Zero(), wd = Vec3<S>::Zero();
    for (int c = t; c < m.speeds; ++c) {
      w += m.angular[c] * y[c];
      wd += m.angular[c] * yd[c] + m.angular_dot[c] * y[c];
    }
    S e1, e2, e3, e4;
    if (uses_euler_parameters(from.joint.type)) {
      e1 = q[t], e2 = q[t + 1], e3 = q[t + 2], e4 = q[t + 3];
    } else {
      quaternion_from_rotation(m.rotation, e1, e2, e3, e4);  // the angles' in their order
    }
    const Vec3<S> e(e1, e2, e3);
    S* qo = out.position.data() + to.q_index + t;
    qo[0] = e1, qo[1] = e2, qo[2] = e3, qo[3] = e4;
    S* vo = out.velocity.data() + to.v_index + t;
    S* ao = out.acceleration.data() + to.v_index + t;
    if (euler_model.speeds == SpeedKind::kAngularVelocity) {
      for (int i = 0; i < 3; ++i) vo[i] = w[i], ao[i] = wd[i];
      continue;
    }
    const Vec3<S> ed = (e4 * w + w.cross(e)) / S(2);  // (0, w) * e / 2, quaternion product
    const S e4d = -w.dot(e) / S(2);
    const Vec3<S> edd = (e4d * w + e4 * wd + wd.cross(e) + w.cross(ed)) / S(2);
    const S e4dd = -(wd.dot(e) + w.dot(ed)) / S(2);
    for (int i = 0; i < 3; ++i) vo[i] = ed[i], ao[i] = edd[i];
    vo[3] = e4d, ao[3] = e4dd;
  }
  return out;
}

}  // namespace mbk
