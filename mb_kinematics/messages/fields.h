// Eigen values into geometry_msgs fields, for the node's outputs and mbk bag alike.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "mb_kinematics/core/types.h"

namespace mbk_messages {

// x, y, z of a Vector3, Point or the like.
template <typename T>
void set_vector(const mbk::Vec3<double>& v, T& out) {
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
}

// set_vector for a message of x, y, z alone (geometry_msgs Vector3, Point), as one copy of its
// 24 bytes: the same values. (Trivially copyable, so its bytes may be copied; its constructor,
// which zeroes them, is what GCC's -Wclass-memaccess sees: hence the void*.)
template <typename T>
void copy_vector(const mbk::Vec3<double>& v, T& out) {
  static_assert(sizeof(T) == 3 * sizeof(double) && std::is_trivially_copyable_v<T> &&
                    std::is_standard_layout_v<T> && offsetof(T, x) == 0 &&
                    offsetof(T, y) == sizeof(double) && offsetof(T, z) == 2 * sizeof(double),
                "copy_vector: a message of x, y, z alone");
  std::memcpy(static_cast<void*>(&out), v.data(), sizeof out);
}

template <typename T>
void set_quaternion(const Eigen::Quaterniond& q, T& out) {
  out.x = q.x();
  out.y = q.y();
  out.z = q.z();
  out.w = q.w();
}

template <typename T>
void set_quaternion(const mbk::Mat3<double>& rotation, T& out) {
  set_quaternion(Eigen::Quaterniond(rotation), out);
}

}  // namespace mbk_messages
