// The recursion's plumbing, shared by kinematics.h, its fast kernels (fast_kernels.h) and their
// AVX2 copy (fast_kernels_avx2.h): Data and the state as raw pointers, the sines and cosines of
// the angles, products with classified constants, and the Newton-Schulz step. None of it is
// doc/method.md's; each is bit for bit the plain Eigen expression it replaces.
#pragma once

#include <vector>

#include "mb_kinematics/core/body_step.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/point_kinematics.h"
#include "mb_kinematics/core/sincos.h"
#include "mb_kinematics/core/state.h"

// The loop over bodies gets every step, sine and Eigen product inlined into it (GCC and Clang
// would otherwise keep body_update and the 3x3 products out of line, their terms in memory).
// Not under AddressSanitizer: flattening the instrumented code makes each translation unit take
// a quarter of an hour to compile (scripts/test.sh --sanitize).
#if defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
#define MBK_FLATTEN __attribute__((flatten))
#else
#define MBK_FLATTEN
#endif

// On x86-64 CPUs with AVX2, the update in double runs as code compiled for them, chosen at run
// time (the build stays portable): the same SSE2 operations in VEX form, whose three operands
// spare the register copies of the two-operand form (about a fifth of the instructions). Without
// FMA, so the same roundings: the results are the same bit for bit.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX2__) && !defined(__SANITIZE_ADDRESS__)
#define MBK_AVX2_DISPATCH 1
#endif

namespace mbk {
namespace detail {

// Every kReorthonormalizeEvery joints of depth (body_step.h), S0K gets one Newton-Schulz step
// back to orthonormal (doc/method.md 4, orientation): R <- R (3 I - R^T R) / 2. Rounding makes S0K
// = S0J SJK drift from orthonormal by about eps per joint, linearly with depth (doc/stability.md);
// one step squares the drift away at the cost of two 3x3 products, here once per 32 levels (cheap
// on long chains, and never on the human model, whose depth is at most 6).
template <typename S>
void reorthonormalize(Mat3<S>& r) {
  const Mat3<S> rtr = transpose_product<S>(r, r);
  r = product<S>(r, S(1.5) * Mat3<S>::Identity() - S(0.5) * rtr);
}

// Where Data keeps a point's motion (the origins', or the mass centers').
template <typename S>
struct PointArrays {
  Vec3<S>*position, *velocity, *acceleration;
};

// Data's arrays as raw pointers, and the state's: the loop over bodies keeps them in registers
// instead of reloading each std::vector's and Eigen vector's start at every access.
template <typename S>
struct DataView {
  Mat3<S>* rotation;
  Vec3<S>*origin, *mass_center, *omega, *alpha, *mass_center_velocity, *mass_center_acceleration,
      *origin_velocity, *origin_acceleration;
  const S *sine, *cosine;  // of BodySteps::angles (angle_sines)
  explicit DataView(Data<S>& d)
      : rotation(d.rotation.data()),
        origin(d.origin.data()),
        mass_center(d.mass_center.data()),
        omega(d.omega.data()),
        alpha(d.alpha.data()),
        mass_center_velocity(d.mass_center_velocity.data()),
        mass_center_acceleration(d.mass_center_acceleration.data()),
        origin_velocity(d.origin_velocity.data()),
        origin_acceleration(d.origin_acceleration.data()),
        sine(d.sine.data()),
        cosine(d.cosine.data()) {}
  PointArrays<S> origins() const { return {origin, origin_velocity, origin_acceleration}; }
  PointArrays<S> centers() const {
    return {mass_center, mass_center_velocity, mass_center_acceleration};
  }
};

// q, y and y' of a JointState (doc/method.md 8).
template <typename S>
struct StateView {
  const S *q, *y, *yd;
  explicit StateView(const JointState<S>& s)
      : q(s.position.data()), y(s.velocity.data()), yd(s.acceleration.data()) {}
  explicit StateView(const S* positions) : q(positions), y(nullptr), yd(nullptr) {}  // poses
};

// The sines and cosines of every angle the kernels turn by (BodySteps::angles), together in one
// loop (sin_cos over an array, bit for bit the one-angle sin_cos).
template <typename S>
void angle_sines(const Model& model, const S* q, Data<S>& data) {
  const std::vector<int>& angles = model.steps.angles;
  const int n = static_cast<int>(angles.size());
  for (int i = 0; i < n; ++i) data.angle[i] = q[angles[i]];
  sin_cos(data.angle.data(), n, data.sine.data(), data.cosine.data());
}

// m v for a constant v of the given shape (body_step.h): bit for bit m * v, whose zero terms
// change no sum.
template <typename S>
Vec3<S> times_constant(const Mat3<S>& m, const Vec3<double>& v, VectorShape shape) {
  switch (shape) {
    case VectorShape::kZero:
      return Vec3<S>::Zero();
    case VectorShape::kX:
      return m.col(0) * S(v.x());
    case VectorShape::kY:
      return m.col(1) * S(v.y());
    case VectorShape::kZ:
      return m.col(2) * S(v.z());
    case VectorShape::kDense:
      break;
  }
  return product<S>(m, v.cast<S>());
}

}  // namespace detail
}  // namespace mbk
