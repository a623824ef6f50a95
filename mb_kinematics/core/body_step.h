// What forward_kinematics does for each body, decided once when the model is finalized: the
// joint's kernel (revolute about x, y or z, prismatic, fixed, ...), so that no update compares
// axes or offset rotations, with constant offset rotations C_k folded into the joint's constants.
#pragma once

#include <cstdint>
#include <vector>

#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

namespace detail {
// Every this many joints of depth, S0K gets one Newton-Schulz step back to orthonormal
// (doc/stability.md; kinematics.h).
constexpr int kReorthonormalizeEvery = 32;
}  // namespace detail

enum class JointKernel : std::uint8_t {
  kFixed,             // SJK = I
  kFixedRotated,      // SJK = C_k
  kRevoluteX,         // C_k = I, axis x: SJK = A(q) (eq. 4.4.9); two columns of S0J turn
  kRevoluteY,         // C_k = I, axis y: SJK = B(q)
  kRevoluteZ,         // C_k = I, axis z: SJK = C(q)
  kRevolute,          // any axis a, C_k: SJK = C_k R(a, q) = P0 + cos q P1 + sin q P2
  kPrismatic,         // C_k = I: SJK = I, s_k = a q
  kPrismaticRotated,  // SJK = C_k, s_k = (C_k a) q
  kBall123,           // SJK = C_k A(alpha) B(beta) C(gamma): one column turn per angle
  kBallEuler,         // SJK = C_k R(e), Euler parameters
  kFree123,           // s_k = C_k (x, y, z), then kBall123
  kFreeEuler,         // s_k = C_k (x, y, z), then kBallEuler
  kBallOrdered,       // angles in another order: kBall123's turns about the order's axes
  kFreeOrdered,       // kFree123's, likewise (euler_order.h EulerTurns)
  kPlanar,            // SJK = P0 + cos q P1 + sin q P2 about the normal, s_k = x C u1 + y C u2
  kGeneric,           // any joint type through joint_motion (a type without a kernel of its own)
};

// Ball and free joints' kernels (angles or Euler parameters): M = S0J C_k, then the rotation.
constexpr bool is_ball_or_free(JointKernel kernel) {
  return kernel == JointKernel::kBall123 || kernel == JointKernel::kBallEuler ||
         kernel == JointKernel::kFree123 || kernel == JointKernel::kFreeEuler ||
         kernel == JointKernel::kBallOrdered || kernel == JointKernel::kFreeOrdered;
}

// Which kernels make_body_steps picks: each type's own where it has one (opt-in, kernel_of in
// body_step.cc), or joint_motion for every body (the generic path the kernels are tested against).
enum class KernelChoice : std::uint8_t { kFast, kGenericOnly };

// Which entries of a constant vector (q_k, r_k) are nonzero, so that S0J q_k takes a column of
// S0J, or nothing, instead of the whole product (the same sums without their zero terms).
enum class VectorShape : std::uint8_t { kZero, kX, kY, kZ, kDense };

struct BodyStep {
  JointKernel kernel = JointKernel::kFixed;
  bool reorthonormalize = false;                   // depth is a multiple of kReorthonormalizeEvery
  VectorShape offset_shape = VectorShape::kDense;  // of offset
  VectorShape mass_center_shape = VectorShape::kDense;  // of mass_center
  int lower = 0;                                        // L(k)
  int q_index = 0;
  int v_index = 0;
  // This body's first constant in BodySteps::matrices: C_k (fixed, prismatic, ball and free
  // joints with C_k != I), P0 P1 P2 (revolute), P0 P1 P2 [C u1, C u2, C a] (planar); else -1.
  int matrices = -1;
  int angle = -1;  // its first angle in BodySteps::angles (revolute, 1-2-3 and planar joints)
  EulerOrder euler_order = EulerOrder::kXYZ;        // kBallOrdered, kFreeOrdered: their order
  Vec3<double> offset = Vec3<double>::Zero();       // q_k, in Bj
  Vec3<double> mass_center = Vec3<double>::Zero();  // r_k, in Bk
  Vec3<double> axis = Vec3<double>::Zero();         // C_k a, in Bj: w_k / q' or s_k' / q'
};

// A 3x3 matrix with each column padded to four doubles, 32-byte aligned: a column is one load
// for the vectorized kernels (vec4.h).
struct alignas(32) PaddedMat3 {
  double col[3][4];
};

struct BodySteps {
  std::vector<BodyStep> steps;  // steps[k] for body Bk; steps[0] unused
  std::vector<Mat3<double>> matrices;
  std::vector<PaddedMat3> padded;  // padded[i]: matrices[i], columns padded
  // The coordinate of every angle the kernels turn by, body by body: forward_kinematics takes
  // their sines and cosines together (Data::sine, Data::cosine) before the bodies.
  std::vector<int> angles;
  bool generic = false;  // some body runs the generic kernel (kinematics_lanes.h: no lanes)
};

}  // namespace mbk
