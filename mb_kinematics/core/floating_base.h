// A floating base measured by odometry (the node's ~base_odometry semantics, doc/node.md): the
// odometry's frame_id is the inertial frame R; the model's root frame (what the model calls R)
// moves with the odometry pose, its twist given in the odometry's child frame (the root frame).
// Poses are interpolated by slerp, twists linearly, at each joint sample's stamp; the base's
// accelerations are the time derivatives of its twist in R, from an estimator over the
// odometry stream (estimation/base_accelerations.h). Then every body's kinematics is carried from
// the root frame into R. ROS-free (Eigen only).
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

// One odometry sample: the root frame's pose in R, its twist in root-frame components.
struct BaseSample {
  double t = 0;
  Vec3<double> position = Vec3<double>::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vec3<double> linear = Vec3<double>::Zero();   // velocity of the root frame's origin
  Vec3<double> angular = Vec3<double>::Zero();  // angular velocity of the root frame
};

// The root frame's motion in R at one instant, every vector in R components.
struct BaseMotion {
  Mat3<double> rotation = Mat3<double>::Identity();
  Vec3<double> position = Vec3<double>::Zero(), velocity = Vec3<double>::Zero(),
               acceleration = Vec3<double>::Zero(), omega = Vec3<double>::Zero(),
               alpha = Vec3<double>::Zero();
};

// The base at time t: slerp of the poses and linear interpolation of the twists (turned into
// R) and of the accelerations between the samples around t. False if t is outside
// [first, last] sample time.
bool interpolate_base(const std::vector<BaseSample>& samples,
                      const std::vector<Vec3<double>>& linear_acceleration,
                      const std::vector<Vec3<double>>& angular_acceleration, double t,
                      BaseMotion& out);

// The base `dt` seconds after sample `s` (before it for dt < 0) with its twist in R held
// constant: R = exp(dt [omega]x) R_s, p = p_s + dt v; the accelerations given are kept. Exact
// for a constant linear velocity and a constant angular velocity about a fixed axis.
void extrapolate_base(const BaseSample& s, const Vec3<double>& linear_acceleration,
                      const Vec3<double>& angular_acceleration, double dt, BaseMotion& out);

// Carries `data` (computed in the root frame) into R for a root frame moving as `base`:
// S0K <- R_b S0K, p <- p_b + R_b p, omega <- w_b + R_b omega, v <- v_b + w_b x R_b p + R_b v,
// alpha <- a_b' + w_b x R_b omega + R_b alpha,
// a <- a_b + alpha_b x R_b p + w_b x (w_b x R_b p) + 2 w_b x R_b v + R_b a.
// Index 0 becomes the root frame's own motion (the root link's mass sits there).
void apply_floating_base(const BaseMotion& base, Data<double>& data);

}  // namespace mbk
