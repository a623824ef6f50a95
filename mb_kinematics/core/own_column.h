// A body's own joint's partial-velocity columns (doc/method.md 5: `S0J W_r` for a rotation speed,
// `S0J t_r` for a translation speed, and `d/dt (S0J W_r) = omega_j x (S0J W_r) + S0J W_r'`), the
// one place both partial_velocity_kinematics (every body) and chain_partial_velocities (chosen
// bodies) take them from.
#pragma once

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

// omega_kr and the partial velocity of O_k for one of body k's own speeds r, and their time
// derivatives, in R; zero where the speed does not act (a translation turns nothing, a rotation
// moves no origin).
template <typename S>
struct OwnColumn {
  Vec3<S> omega, origin_velocity, omega_dot, origin_velocity_dot;
};

// Speed c of the joint in motion `m` (joint_motion.h), below a lower body of rotation S0J and
// angular velocity omega_j; `column`: S0J times the joint's column c (a kernel may give it
// through its own products, as ball and free joints do through M = S0J C_k).
template <typename S>
OwnColumn<S> own_column(const JointMotion<S>& m, int c, const Vec3<S>& column, const Mat3<S>& s0j,
                        const Vec3<S>& omega_j) {
  const Vec3<S> zero = Vec3<S>::Zero(), turned = omega_j.cross(column);
  if (c < m.linear_speeds) return {zero, column, zero, turned};
  return {column, zero, Vec3<S>(turned + s0j * m.angular_dot[c]), zero};
}

// The same column from m alone: S0J times its linear or angular column c.
template <typename S>
Vec3<S> joint_column(const JointMotion<S>& m, int c, const Mat3<S>& s0j) {
  return s0j * (c < m.linear_speeds ? m.linear[c] : m.angular[c]);
}

}  // namespace mbk
