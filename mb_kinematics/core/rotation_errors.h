// First-order error bars of the bodies moved by a ball or free joint on angles, from the errors
// of the joint's rotation rather than of each angle (doc/method.md 11). Near gimbal lock the
// angles' errors are large and strongly correlated (two angles turn about nearly the same axis),
// while the rotation they describe is as good as elsewhere: the errors are carried as the joint's
// small rotation dtheta of SJK, its relative angular velocity w and that one's rate w' (Bj axes),
// and from there to every body outward of the joint. No allocation.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"

namespace mbk {

using Mat9 = Eigen::Matrix<double, 9, 9>;

// E(q) of a joint that takes an Euler order (takes_euler_order): w = E q' in Bj axes (C_k
// included), and the small rotation of SJK made by angle errors dq is E dq. angles: its three.
Mat3<double> angle_rate_matrix(const Joint& joint, const double* angles);

// The first-order map L from the errors (dq, dq', dq'') of the joint's three angles to those of
// (dtheta, dw, dw'): L = [[E, 0, 0], [dw/dq, E, 0], [dw'/dq, dw'/dq', E]], w = E q' and
// w' = E q'' + E' q' at (q, q', q'') (the derivatives by central differences).
Mat9 angle_error_map(const Joint& joint, const double* q, const double* qd, const double* qdd);

// Adds to the variances of each R component of alpha_k and of the mass-center acceleration a_k,
// for body b and every body outward of it, those that the errors (dtheta, dw, dw') of b's joint
// with covariance `cov` (Bj axes) make, the rest exact. data: forward_kinematics of the state at
// Level::kAcceleration. subtree: scratch (resized to the bodies once).
void add_joint_rotation_variance(const Model& model, const Data<double>& data, int b,
                                 const Mat9& cov, std::vector<Vec3<double>>& alpha_var,
                                 std::vector<Vec3<double>>& acceleration_var,
                                 std::vector<char>& subtree);

}  // namespace mbk
