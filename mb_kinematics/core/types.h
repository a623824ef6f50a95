// Small fixed-size Eigen types used across the core, templated on the scalar.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mbk {

template <typename S>
using Vec3 = Eigen::Matrix<S, 3, 1>;
template <typename S>
using Mat3 = Eigen::Matrix<S, 3, 3>;
template <typename S>
using VecX = Eigen::Matrix<S, Eigen::Dynamic, 1>;

// Skew-symmetric matrix [v]x with [v]x u = v x u.
template <typename S>
Mat3<S> skew(const Vec3<S>& v) {
  Mat3<S> m;
  m << S(0), -v.z(), v.y(), v.z(), S(0), -v.x(), -v.y(), v.x(), S(0);
  return m;
}

}  // namespace mbk
