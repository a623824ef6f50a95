// Central inertia matrices of the bodies: built from the six components (URDF's convention: the
// matrix entries, products of inertia with their sign) and checked for being physical.
#pragma once

#include <string>

#include "mb_kinematics/core/types.h"

namespace mbk {

// [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]].
Mat3<double> inertia_matrix(double ixx, double iyy, double izz, double ixy, double ixz, double iyz);

// "" if `inertia` is a physical central inertia: finite, symmetric, and its principal moments
// satisfy the triangle inequality I1 + I2 >= I3 (which makes them >= 0, so it is positive
// semidefinite), each to 1e-9 of the trace; otherwise what is wrong, with the principal moments.
std::string inertia_problem(const Mat3<double>& inertia);

}  // namespace mbk
