// A quaternion whose largest component exceeds 1 scaled down so that it is +-1: the same rotation
// (q and s q, s > 0, are one rotation), and its norm no longer overflows (components of 1e154
// and more square to Inf, and Eigen's normalize() would then give zero, read as identity).
// Smaller quaternions, NaN and Inf are left as they are for the caller's own checks.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace mbk {

inline void scale_large_quaternion(Eigen::Quaterniond& q) {
  const double largest = q.coeffs().cwiseAbs().maxCoeff();
  if (std::isfinite(largest) && largest > 1) q.coeffs() /= largest;
}

}  // namespace mbk
