// Validation of a joint state before the kinematics (doc/stability.md): what the
// recursion cannot turn into finite, meaningful numbers is rejected with a message naming the
// joint and the coordinate, instead of being published as NaN/Inf. ROS-free; no allocation
// unless a message is returned.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

// Euler parameters e1..e4 of |e|^2 below this are rejected. The formulas divide by |e|^2 and
// are scale-invariant in exact arithmetic (and in double down to |e|^2 ~ 1e-290, where the
// squares underflow), so the limit is not a need of the arithmetic: Euler parameters are meant
// to have norm 1 and drift from it only by rounding (~1e-16 per update), so |e| < 1e-6 is a
// zero, uninitialized or corrupted value, not a rotation. It also caps the amplification of
// the parameters' own absolute errors (>= 1.1e-16 when produced at unit scale) into the
// orientation, 1/|e| <= 1e6 (orientation error <= ~1e-10), and of e' into omega, 2/|e|^2.
constexpr double kMinEulerNormSquared = 1e-12;

// Every coordinate other than an angle (translations, Euler parameters), and every speed and
// acceleration, must be at most this in magnitude. The recursion forms products of up to three
// such factors (omega_j x (omega_j x d_k): 1e150) and sums them over the bodies, so with model
// lengths up to 1e50 and any practical number of bodies nothing overflows (DBL_MAX ~ 1.8e308).
// Angles (revolute, 1-2-3, planar gamma) may be any finite value: sin and cos are bounded and
// glibc reduces even 1e308 rad correctly. A prismatic travel of 1e308 m would overflow in
// O_k = O_j + d_k; it is rejected here rather than published as Inf.
constexpr double kMaxStateMagnitude = 1e50;

// "" if `state` (sized by `model`) can be evaluated, else a one-line message such as
// "body 2 'arm', coordinate 'shoulder/e1..e4': Euler parameters of |e|^2 = 0, below 1e-12
// (not a rotation)" or "body 1 'base', speed 'slide': not finite (nan)".
std::string check_state(const Model& model, const JointState<double>& state);

}  // namespace mbk
