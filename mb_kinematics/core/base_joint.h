// The floating base as a free joint of the model (doc/node.md "Floating base from odometry"): the
// node gives the model a body on a free joint from R (or uses a URDF's floating root joint) and
// turns the base's motion (core/floating_base.h) into that joint's coordinates, so that the
// unchanged recursion (doc/method.md 4) gives every body's kinematics in R, base included, and
// the partial velocities have the base's speeds. ROS-free (Eigen only).
#pragma once

#include <string>

#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/core/model.h"

namespace mbk {

// Whether the model's base is already a free joint: body 1 on a free_123 or free_euler joint,
// the only body on R (a URDF whose root joint is `floating`).
bool has_floating_root(const Model& model);

// The model with a new body 1 on a free_euler joint named `joint` from R, named after the
// model's R (its root link, whose mass, mass center and inertia it carries), and R renamed `frame`:
// the old bodies follow it, its coordinates come first (`joint`/x y z e1 e2 e3 e4), mimics follow
// their coordinates.
Model with_floating_base(const Model& model, const std::string& frame, const std::string& joint);

// The model without body 1 (the floating base of has_floating_root): its children hang from R,
// which takes body 1's name; the coordinates of body 1's joint are gone. The joint states of the
// other bodies of a has_floating_root model fill this model's state, in the same order.
Model without_root_body(const Model& model);

// The coordinates, first and second derivatives of a free joint (free_123 or free_euler, with
// its offset q_k and rotation C_k) from R that put its body at `m` (doc/method.md 2: SJK = C_k
// R_motion, origin q_k + C_k s_k); qdd may be null (then no accelerations). Returns an error
// for other joints and for angles at gimbal lock (|cos(beta + shift)| < 1e-9, euler_order.h).
std::string free_joint_coordinates(const Joint& joint, const BaseMotion& m, double* q, double* qd,
                                   double* qdd);

}  // namespace mbk
