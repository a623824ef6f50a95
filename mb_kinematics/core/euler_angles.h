// Cardan/Euler angles of a rotation in any of the 12 orders of core/euler_order.h, the inverse of
// R = R_a1(alpha) R_a2(beta) R_a3(gamma) (intrinsic turns, as the joints'), and a time series of
// them kept continuous (joint angles: doc/method.md 10). ROS-free (Eigen only).
//
// Through the order's EulerMap: R = P R_123(alpha, beta + shift, sign gamma) Q, so the 1-2-3
// angles (eq. 4.4.9-4.4.12) of P^T R Q^T give them. Every rotation has two sets, (alpha, beta,
// gamma) and (alpha + pi, pi - beta, gamma + pi) for Tait-Bryan orders, (alpha + pi, -beta,
// gamma + pi) for proper Euler orders, each up to 2 pi in any angle; at gimbal lock (Tait-Bryan
// beta = +-pi/2, proper Euler beta = 0 or pi) only alpha + gamma or alpha - gamma is defined.
#pragma once

#include <cstddef>
#include <vector>

#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

// The principal angles: alpha, gamma in [-pi, pi]; beta in [-pi/2, pi/2] (Tait-Bryan) or
// [0, pi] (proper Euler); at gimbal lock alpha = 0. `r` must be a rotation (orthonormal, det 1).
Vec3<double> euler_angles(const Mat3<double>& r, EulerOrder order);

// The angles of `r` nearest `previous` (the last sample's): of the two sets, each angle moved by
// the multiple of 2 pi nearest `previous`, the set closer to it (sum of squares); at gimbal lock
// alpha = previous alpha. A series of rotations that changes little between samples so gets
// angles without 2 pi jumps, and through a gimbal lock without the swap of sets.
Vec3<double> euler_angles_near(const Mat3<double>& r, EulerOrder order,
                               const Vec3<double>& previous);

// The angles of several series of rotations (a body's joint rotations, row after row), each
// series' first principal (euler_angles), each next one nearest the series' last
// (euler_angles_near): continuous, as mbk bag's --angles and --mot write them.
class EulerAngleTrack {
 public:
  // orders[s]: series s's order.
  explicit EulerAngleTrack(std::vector<EulerOrder> orders);
  // Series s's angles at its next rotation `r` (kept as its last).
  const Vec3<double>& next(std::size_t s, const Mat3<double>& r);
  const Vec3<double>& last(std::size_t s) const { return angles_[s]; }
  EulerOrder order(std::size_t s) const { return orders_[s]; }
  std::size_t size() const { return orders_.size(); }

 private:
  std::vector<EulerOrder> orders_;
  std::vector<Vec3<double>> angles_;
  std::vector<char> started_;  // per series: a rotation was given
};

// Row-major rotations (samples, series, 3, 3) into angles (samples, series, 3): the first sample's
// principal, each next one euler_angles_near the sample before, series s in orders[s] (one order
// for all when orders has one entry).
void euler_angle_series(const double* rotations, std::size_t samples, std::size_t series,
                        const std::vector<EulerOrder>& orders, double* angles);

// R_a1(alpha) R_a2(beta) R_a3(gamma) in `order`.
Mat3<double> rotation_from_euler_angles(const Vec3<double>& angles, EulerOrder order);

}  // namespace mbk
