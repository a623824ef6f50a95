// Absolute kinematics by the O(N) outward recursion along the lower body array (doc/method.md 4).
// Each body runs its joint's kernel, chosen once when the model was finalized (body_step.h).
#pragma once

#include <cassert>
#include <cmath>
#include <limits>
#include <type_traits>

#include "mb_kinematics/core/body_step.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/model.h"
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

#include "mb_kinematics/core/vec4.h"  // its kernels, for the AVX2 copy

namespace mbk {
namespace detail {

// Every kReorthonormalizeEvery joints of depth (body_step.h), S0K gets one Newton-Schulz step
// back to orthonormal: R <- R (3 I - R^T R) / 2. Rounding makes S0K = S0J SJK drift from
// orthonormal by about eps per joint, linearly with depth (doc/stability.md); one
// step squares the drift away at the cost of two 3x3 products, here once per 32 levels (cheap on
// long chains, and never on the human model, whose depth is at most 6).
template <typename S>
void reorthonormalize(Mat3<S>& r) {
  const Mat3<S> rtr = r.transpose() * r;
  r = r * (S(1.5) * Mat3<S>::Identity() - S(0.5) * rtr);
}

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
};

// q, y and y' of a JointState (doc/method.md 8).
template <typename S>
struct StateView {
  const S *q, *y, *yd;
  explicit StateView(const JointState<S>& s)
      : q(s.position.data()), y(s.velocity.data()), yd(s.acceleration.data()) {}
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
  return m * v.cast<S>();
}

// A joint's share of body k's motion, in R components: d = S0J (q_k + s_k) (O_j to O_k), the
// relative angular velocity w = S0J w_k and w' part wd = S0J w_k', and sd = S0J s_k',
// sdd = S0J s_k''.
template <typename S>
struct JointTerms {
  Vec3<S> d, w, wd, sd, sdd;
};

// O_k and its velocity and acceleration from O_j's (doc/method.md 4, eq. 4.6.2): d = 0 (a joint
// at O_j that does not translate) leaves them O_j's.
template <Level L, bool kTranslates, typename S>
void origin_update(const BodyStep& b, int k, const JointTerms<S>& t, const DataView<S>& data) {
  const int j = b.lower;
  if (!kTranslates && b.offset_shape == VectorShape::kZero) {
    data.origin[k] = data.origin[j];
    if constexpr (L != Level::kPose) data.origin_velocity[k] = data.origin_velocity[j];
    if constexpr (L == Level::kAcceleration)
      data.origin_acceleration[k] = data.origin_acceleration[j];
    return;
  }
  data.origin[k] = data.origin[j] + t.d;  // eq. 4.6.2
  if constexpr (L != Level::kPose) {
    const Vec3<S>& omega_j = data.omega[j];
    const Vec3<S> omega_j_d = omega_j.cross(t.d);
    Vec3<S>& vo = data.origin_velocity[k];
    vo = data.origin_velocity[j] + omega_j_d;
    if constexpr (kTranslates) vo += t.sd;
    if constexpr (L == Level::kAcceleration) {
      Vec3<S>& ao = data.origin_acceleration[k];
      ao = data.origin_acceleration[j] + data.alpha[j].cross(t.d) + omega_j.cross(omega_j_d);
      if constexpr (kTranslates) ao += S(2) * omega_j.cross(t.sd) + t.sdd;
    }
  }
}

// G_k and its velocity and acceleration from O_k's, rho = S0K r_k (doc/method.md 4): r_k = 0
// leaves them O_k's.
template <Level L, typename S>
void mass_center_update(const BodyStep& b, int k, const DataView<S>& data) {
  if (b.mass_center_shape == VectorShape::kZero) {
    data.mass_center[k] = data.origin[k];
    if constexpr (L != Level::kPose) data.mass_center_velocity[k] = data.origin_velocity[k];
    if constexpr (L == Level::kAcceleration)
      data.mass_center_acceleration[k] = data.origin_acceleration[k];
    return;
  }
  const Vec3<S> rho = times_constant(data.rotation[k], b.mass_center, b.mass_center_shape);
  data.mass_center[k] = data.origin[k] + rho;
  if constexpr (L != Level::kPose) {
    const Vec3<S>& omega_k = data.omega[k];
    const Vec3<S> omega_k_rho = omega_k.cross(rho);
    data.mass_center_velocity[k] = data.origin_velocity[k] + omega_k_rho;
    if constexpr (L == Level::kAcceleration)
      data.mass_center_acceleration[k] =
          data.origin_acceleration[k] + data.alpha[k].cross(rho) + omega_k.cross(omega_k_rho);
  }
}

// Body k from its lower body once S0K = S0J SJK is in data.rotation[k] (doc/method.md 4).
// kRotates, kTranslates: whether the joint turns (w, wd used) and translates (sd, sdd used).
template <Level L, bool kRotates, bool kTranslates, typename S>
void body_update(const BodyStep& b, int k, const JointTerms<S>& t, const DataView<S>& data) {
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);
  if constexpr (L != Level::kPose) {
    const Vec3<S>& omega_j = data.omega[j];
    Vec3<S>& omega_k = data.omega[k];
    omega_k = omega_j;
    if constexpr (kRotates) omega_k += t.w;  // eq. 4.4.6
    if constexpr (L == Level::kAcceleration) {
      if constexpr (kRotates)
        data.alpha[k] = data.alpha[j] + t.wd + omega_j.cross(t.w);  // eq. 4.5.1
      else
        data.alpha[k] = data.alpha[j];
    }
  }
  origin_update<L, kTranslates>(b, k, t, data);
  mass_center_update<L>(b, k, data);
}

// S0K = S0J SJK for a turn (cos c, sin s) about coordinate axis I with C_k = I (eq. 4.4.9-4.4.11
// column by column): column I of S0J stays, the other two turn.
template <int I, typename S>
void turn_columns(const Mat3<S>& s0j, S c, S s, Mat3<S>& s0k) {
  constexpr int a = (I + 1) % 3, b = (I + 2) % 3;
  s0k.col(I) = s0j.col(I);
  s0k.col(a) = c * s0j.col(a) + s * s0j.col(b);
  s0k.col(b) = c * s0j.col(b) - s * s0j.col(a);
}

// The pose part of each kernel: S0K into data.rotation[k] and d = S0J (q_k + s_k). Both
// formulations (this recursion and partial_velocity_kinematics) use them, and so agree bit for
// bit. q: all coordinates.

// Revolute joint about coordinate axis I, C_k = I.
template <int I, typename S>
void axis_pose(const BodyStep& b, int k, const DataView<S>& data, Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  turn_columns<I>(s0j, data.cosine[b.angle], data.sine[b.angle], data.rotation[k]);
  d = times_constant(s0j, b.offset, b.offset_shape);
}

// S0K = S0J SJK for a turn (cos c, sin s) about any axis a with any C_k: SJK = P0 + c P1 +
// s P2 (p: P0 P1 P2, body_step.cc).
template <typename S>
void folded_turn(const Mat3<double>* p, const Mat3<S>& s0j, S c, S s, Mat3<S>& s0k) {
  const Mat3<S> sjk = p[0].cast<S>() + c * p[1].cast<S>() + s * p[2].cast<S>();
  s0k = s0j * sjk;
}

// Revolute joint about any axis a with any C_k.
template <typename S>
void revolute_pose(const Model& model, const BodyStep& b, int k, const DataView<S>& data,
                   Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  folded_turn(model.steps.matrices.data() + b.matrices, s0j, data.cosine[b.angle],
              data.sine[b.angle], data.rotation[k]);
  d = times_constant(s0j, b.offset, b.offset_shape);
}

// Planar joint (x, y, gamma): the turn about the normal as a revolute joint's, and
// d = S0J (q_k + x C u1 + y C u2) with the plane's axes folded at load (body_step.cc).
template <typename S>
void planar_pose(const Model& model, const BodyStep& b, int k, const S* q, const DataView<S>& data,
                 Vec3<S>& d) {
  const Mat3<double>* p = model.steps.matrices.data() + b.matrices;
  const Mat3<S>& s0j = data.rotation[b.lower];
  const S* x = q + b.q_index;
  folded_turn(p, s0j, data.cosine[b.angle], data.sine[b.angle], data.rotation[k]);
  d = s0j * (b.offset.cast<S>() + p[3].col(0).cast<S>() * x[0] + p[3].col(1).cast<S>() * x[1]);
}

// A ball or free joint's frames in R components: M = S0J C_k, and for angles in the order
// (a1, a2, a3) the turns M R_a1 (after alpha) and M R_a1 R_a2 (after beta); kappa, the factor of
// alpha' a1 in a2' (angles_rates).
template <typename S>
struct BallFrame {
  Mat3<S> m, ma, mab;
  S kappa;
};

// Angles in the order O (euler_order.h EulerTurns): S0K = M R_a1(alpha) R_a2(beta) R_a3(gamma),
// one column turn per angle about the order's axes (eq. 4.4.9-4.4.12 for 1-2-3 = XYZ: every
// order is the same code at other axes). c, s: the angles' cosines and sines.
template <EulerOrder O, typename S>
void angles_pose(const S* c, const S* s, BallFrame<S>& f, Mat3<S>& s0k) {
  constexpr EulerTurns o = euler_turns(O);
  turn_columns<o.a1>(f.m, c[0], s[0], f.ma);
  turn_columns<o.a2>(f.ma, c[1], s[1], f.mab);
  turn_columns<o.a3>(f.mab, c[2], s[2], s0k);
  f.kappa = o.proper ? s[1] : o.sigma == 1 ? -c[1] : c[1];  // -sigma cos beta, or sin beta
}

template <JointKernel K>
constexpr bool kFreeJoint =
    K == JointKernel::kFree123 || K == JointKernel::kFreeEuler || K == JointKernel::kFreeOrdered;
template <JointKernel K>
constexpr bool kAngles = K == JointKernel::kBall123 || K == JointKernel::kFree123 ||
                         K == JointKernel::kBallOrdered || K == JointKernel::kFreeOrdered;

// Ball and free joints: M = S0J C_k, S0K = M R with R of the angles in the order O or of the
// Euler parameters, d = S0J q_k + M s with s = (x, y, z) for free joints (along the joint frame's
// axes).
template <JointKernel K, EulerOrder O = EulerOrder::kXYZ, typename S>
void ball_pose(const Model& model, const BodyStep& b, int k, const S* q, const DataView<S>& data,
               BallFrame<S>& f, Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  const S* x = q + b.q_index;
  const S* angles = kFreeJoint<K> ? x + 3 : x;
  if (b.matrices >= 0)
    f.m = s0j * model.steps.matrices[b.matrices].cast<S>();  // C_k
  else
    f.m = s0j;
  if constexpr (kAngles<K>)
    angles_pose<O>(data.cosine + b.angle, data.sine + b.angle, f, data.rotation[k]);
  else
    data.rotation[k] = f.m * rotation_euler(angles);
  d = times_constant(s0j, b.offset, b.offset_shape);
  if constexpr (kFreeJoint<K>) d += f.m * Vec3<S>(x[0], x[1], x[2]);
}

// Prismatic (kTranslates) or fixed joint: SJK = C_k (I when not kRotated), s_k = (C_k a) q.
template <bool kRotated, bool kTranslates, typename S>
void rigid_pose(const Model& model, const BodyStep& b, int k, const S* q, const DataView<S>& data,
                Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  if constexpr (kRotated)
    data.rotation[k] = s0j * model.steps.matrices[b.matrices].cast<S>();
  else
    data.rotation[k] = s0j;
  if constexpr (kTranslates)
    d = s0j * (b.offset.cast<S>() + b.axis.cast<S>() * q[b.q_index]);
  else
    d = times_constant(s0j, b.offset, b.offset_shape);
}

// Any joint from its joint_motion.
template <typename S>
void motion_pose(const BodyStep& b, int k, const JointMotion<S>& m, const DataView<S>& data,
                 Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  data.rotation[k] = s0j * m.rotation;             // S0K = S0J SJK
  d = s0j * (b.offset.cast<S>() + m.translation);  // S0J (q_k + s_k)
}

// Constants folded in double (P0 P1 P2, C_k a, the plane's axes) serve double and float;
// wider reference builds take those joints through joint_motion, on the model's own C_k and axis.
template <typename S>
constexpr bool kFolded = std::numeric_limits<S>::digits <= std::numeric_limits<double>::digits;

// Whether body k's kernel runs through joint_motion.
template <typename S>
bool uses_joint_motion(JointKernel kernel) {
  return kernel == JointKernel::kGeneric ||
         (!kFolded<S> &&
          (kernel == JointKernel::kRevolute || kernel == JointKernel::kPrismaticRotated ||
           kernel == JointKernel::kPlanar));
}

// Orientation, origin and mass center of body k by its kernel (m: its joint_motion, used when
// uses_joint_motion); also returns d = S0J (q_k + s_k), rho = S0K r_k and, for ball and free
// joints, their frames f. For partial_velocity_kinematics.
template <typename S>
MBK_FLATTEN void pose_step(const Model& model, int k, const S* q, const JointMotion<S>& m,
                           Data<S>& all, Vec3<S>& d, Vec3<S>& rho, BallFrame<S>& f) {
  const DataView<S> data(all);
  const BodyStep& b = model.steps.steps[k];
  if (uses_joint_motion<S>(b.kernel)) {
    motion_pose(b, k, m, data, d);
  } else {
    switch (b.kernel) {
      case JointKernel::kRevoluteX:
        axis_pose<0>(b, k, data, d);
        break;
      case JointKernel::kRevoluteY:
        axis_pose<1>(b, k, data, d);
        break;
      case JointKernel::kRevoluteZ:
        axis_pose<2>(b, k, data, d);
        break;
      case JointKernel::kRevolute:
        revolute_pose(model, b, k, data, d);
        break;
      case JointKernel::kPrismatic:
        rigid_pose<false, true>(model, b, k, q, data, d);
        break;
      case JointKernel::kPrismaticRotated:
        rigid_pose<true, true>(model, b, k, q, data, d);
        break;
      case JointKernel::kFixed:
        rigid_pose<false, false>(model, b, k, q, data, d);
        break;
      case JointKernel::kFixedRotated:
        rigid_pose<true, false>(model, b, k, q, data, d);
        break;
      case JointKernel::kBall123:
        ball_pose<JointKernel::kBall123>(model, b, k, q, data, f, d);
        break;
      case JointKernel::kBallEuler:
        ball_pose<JointKernel::kBallEuler>(model, b, k, q, data, f, d);
        break;
      case JointKernel::kFree123:
        ball_pose<JointKernel::kFree123>(model, b, k, q, data, f, d);
        break;
      case JointKernel::kFreeEuler:
        ball_pose<JointKernel::kFreeEuler>(model, b, k, q, data, f, d);
        break;
      case JointKernel::kBallOrdered:
        with_euler_order(b.euler_order, [&](auto o) {
          ball_pose<JointKernel::kBall123, decltype(o)::value>(model, b, k, q, data, f, d);
        });
        break;
      case JointKernel::kFreeOrdered:
        with_euler_order(b.euler_order, [&](auto o) {
          ball_pose<JointKernel::kFree123, decltype(o)::value>(model, b, k, q, data, f, d);
        });
        break;
      case JointKernel::kPlanar:
        planar_pose(model, b, k, q, data, d);
        break;
      case JointKernel::kGeneric:  // uses_joint_motion
        motion_pose(b, k, m, data, d);
        break;
    }
  }
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);
  data.origin[k] = data.origin[j] + d;                                         // eq. 4.6.2
  rho = times_constant(data.rotation[k], b.mass_center, b.mass_center_shape);  // S0K r_k
  data.mass_center[k] = data.origin[k] + rho;
}

// Revolute joint about coordinate axis I, C_k = I: w_k = e_I q', so S0J w_k = column I of S0J q'.
template <Level L, int I, typename S>
void revolute_axis_step(const BodyStep& b, int k, const StateView<S>& state,
                        const DataView<S>& data) {
  JointTerms<S> t;
  axis_pose<I>(b, k, data, t.d);
  const Mat3<S>& s0j = data.rotation[b.lower];
  if constexpr (L != Level::kPose) t.w = s0j.col(I) * state.y[b.v_index];
  if constexpr (L == Level::kAcceleration) t.wd = s0j.col(I) * state.yd[b.v_index];
  body_update<L, true, false>(b, k, t, data);
}

// Revolute joint about any axis: S0J w_k = S0J (C_k a) q'.
template <Level L, typename S>
void revolute_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                   const DataView<S>& data) {
  JointTerms<S> t;
  revolute_pose(model, b, k, data, t.d);
  if constexpr (L != Level::kPose) {
    const Vec3<S> u = data.rotation[b.lower] * b.axis.cast<S>();
    t.w = u * state.y[b.v_index];
    if constexpr (L == Level::kAcceleration) t.wd = u * state.yd[b.v_index];
  }
  body_update<L, true, false>(b, k, t, data);
}

// Prismatic joint: s_k' = (C_k a) q'.
template <Level L, bool kRotated, typename S>
void prismatic_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                    const DataView<S>& data) {
  JointTerms<S> t;
  rigid_pose<kRotated, true>(model, b, k, state.q, data, t.d);
  if constexpr (L != Level::kPose) {
    const Vec3<S> u = data.rotation[b.lower] * b.axis.cast<S>();
    t.sd = u * state.y[b.v_index];
    if constexpr (L == Level::kAcceleration) t.sdd = u * state.yd[b.v_index];
  }
  body_update<L, false, true>(b, k, t, data);
}

// Fixed joint.
template <Level L, bool kRotated, typename S>
void fixed_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                const DataView<S>& data) {
  JointTerms<S> t;
  rigid_pose<kRotated, false>(model, b, k, state.q, data, t.d);
  body_update<L, false, false>(b, k, t, data);
}

// Any joint through joint_motion, column by column: the generic path (JointKernel::kGeneric),
// and the folded joints of a reference build.
template <Level L, typename S>
void motion_step(const Model& model, int k, const StateView<S>& state, const DataView<S>& data) {
  const Body& body = model.bodies[k];
  const BodyStep& b = model.steps.steps[k];
  const S* y = L == Level::kPose ? nullptr : state.y + body.v_index;
  JointMotion<S> m;
  joint_motion(body.joint, model.speeds, state.q + body.q_index, y, m);
  JointTerms<S> t;
  motion_pose(b, k, m, data, t.d);
  const Mat3<S>& s0j = data.rotation[b.lower];
  if constexpr (L != Level::kPose) {
    Vec3<S> w = Vec3<S>::Zero(), sd = Vec3<S>::Zero();  // w_k, s_k' in Bj
    for (int c = m.linear_speeds; c < m.speeds; ++c) w += m.angular[c] * y[c];
    for (int c = 0; c < m.linear_speeds; ++c) sd += m.linear[c] * y[c];
    t.w = s0j * w;
    t.sd = s0j * sd;
    if constexpr (L == Level::kAcceleration) {
      const S* yd = state.yd + body.v_index;
      Vec3<S> wd = Vec3<S>::Zero(), sdd = Vec3<S>::Zero();  // w_k', s_k'' in Bj
      for (int c = m.linear_speeds; c < m.speeds; ++c)
        wd += m.angular[c] * yd[c] + m.angular_dot[c] * y[c];
      for (int c = 0; c < m.linear_speeds; ++c) sdd += m.linear[c] * yd[c];
      t.wd = s0j * wd;
      t.sdd = s0j * sdd;
    }
  }
  if (m.linear_speeds > 0)  // the s_k' terms vanish otherwise
    body_update<L, true, true>(b, k, t, data);
  else
    body_update<L, true, false>(b, k, t, data);
}

// w_k and the w_k' part of angles in the order O in R (eq. 4.4.13-4.4.16 for 1-2-3): the
// columns e_a1, R_a1 e_a2, R_a1 R_a2 e_a3 carried by M are u0 = M e_a1, u1 = (M R_a1) e_a2,
// u2 = (M R_a1 R_a2) e_a3, and their rates (eq. 4.5; R_a' = R_a [e_a]x angle') are
// u1' = alpha' (M R_a1) (e_a1 x e_a2) = sigma alpha' (M R_a1) e_third and u2' = kappa alpha' u1 +
// beta' (M R_a1 R_a2) (e_a2 x e_a3), e_a2 x e_a3 = sigma e_a1 (Tait-Bryan) or -sigma e_third
// (proper Euler); linear in M, as C_k (angular_dot) carries them in joint_motion. Each sign is a
// constant: a sum or a difference.
template <Level L, EulerOrder O, typename S>
void angles_rates(const BallFrame<S>& f, const S* y, const S* yd, JointTerms<S>& t) {
  constexpr EulerTurns o = euler_turns(O);
  const Vec3<S> u0 = f.m.col(o.a1), u1 = f.ma.col(o.a2), u2 = f.mab.col(o.a3);
  t.w = u0 * y[0] + u1 * y[1] + u2 * y[2];
  if constexpr (L == Level::kAcceleration) {
    const Vec3<S> u1_dot = f.ma.col(o.third) * y[0];  // times sigma
    const Vec3<S> turned = f.mab.col(o.proper ? o.third : o.a1) * y[1];
    constexpr bool u2_plus = o.proper ? o.sigma == -1 : o.sigma == 1;  // e_a2 x e_a3 sign
    const Vec3<S> u2_dot =
        u2_plus ? Vec3<S>(u1 * (f.kappa * y[0]) + turned) : Vec3<S>(u1 * (f.kappa * y[0]) - turned);
    const Vec3<S> sum = u0 * yd[0] + u1 * yd[1] + u2 * yd[2];
    t.wd = o.sigma == 1 ? Vec3<S>(sum + u1_dot * y[1] + u2_dot * y[2])
                        : Vec3<S>(sum - u1_dot * y[1] + u2_dot * y[2]);
  }
}

// Ball and free joints (ball_pose): the rates of the angles in R (from their columns, any order;
// Euler parameters in the joint frame and then M), and s_k' = M (x', y', z'). O: as for
// ball_pose.
template <Level L, JointKernel K, EulerOrder O = EulerOrder::kXYZ, typename S>
void ball_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
               const DataView<S>& data) {
  JointTerms<S> t;
  BallFrame<S> f;
  ball_pose<K, O>(model, b, k, state.q, data, f, t.d);
  if constexpr (L != Level::kPose) {
    constexpr int kAngular = kFreeJoint<K> ? 3 : 0;  // the angles' first coordinate and speed
    const S *y = state.y + b.v_index, *yd = state.yd + b.v_index;
    if constexpr (kAngles<K>) {
      angles_rates<L, O>(f, y + kAngular, yd + kAngular, t);
    } else {
      Vec3<S> w, wd = Vec3<S>::Zero();  // wd: set only at kAcceleration
      detail::euler_rates(state.q + b.q_index + kAngular, y + kAngular,
                          L == Level::kAcceleration ? yd + kAngular : nullptr, model.speeds, w, wd);
      t.w = f.m * w;
      if constexpr (L == Level::kAcceleration) t.wd = f.m * wd;
    }
    if constexpr (kFreeJoint<K>) {
      t.sd = f.m * Vec3<S>(y[0], y[1], y[2]);
      if constexpr (L == Level::kAcceleration) t.sdd = f.m * Vec3<S>(yd[0], yd[1], yd[2]);
    }
  }
  body_update<L, true, kFreeJoint<K>>(b, k, t, data);
}

// Column c of a ball or free joint's speeds in R, as ball_step sums them for a unit speed y_c
// (bit for bit): M e_c for a translation, else u_c (angles, any order: angles_rates) or M times
// the Euler parameters' column. For partial_velocity_kinematics; f from pose_step, e: the Euler
// parameters.
template <typename S>
Vec3<S> ball_column(const BodyStep& b, SpeedKind speeds, const BallFrame<S>& f, const S* e, int c) {
  const JointKernel kernel = b.kernel;
  const bool free = kernel == JointKernel::kFree123 || kernel == JointKernel::kFreeEuler ||
                    kernel == JointKernel::kFreeOrdered;
  const int angle = free ? c - 3 : c;
  if (angle < 0) return f.m * Vec3<S>::Unit(c);
  if (kernel != JointKernel::kBallEuler && kernel != JointKernel::kFreeEuler) {
    const std::array<int, 3> a = euler_axes(b.euler_order);
    return angle == 0 ? f.m.col(a[0]) : angle == 1 ? f.ma.col(a[1]) : f.mab.col(a[2]);
  }
  Vec3<S> angular[4];
  detail::euler_columns<S>(e, nullptr, speeds, angular, nullptr);
  return f.m * angular[angle];
}

// Planar joint (planar_pose): w = (S0J C a) gamma', s_k' = S0J (C u1 x' + C u2 y').
template <Level L, typename S>
void planar_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                 const DataView<S>& data) {
  JointTerms<S> t;
  planar_pose(model, b, k, state.q, data, t.d);
  if constexpr (L != Level::kPose) {
    const Mat3<S>& s0j = data.rotation[b.lower];
    const Vec3<S> u1 = model.steps.matrices[b.matrices + 3].col(0).cast<S>();
    const Vec3<S> u2 = model.steps.matrices[b.matrices + 3].col(1).cast<S>();
    const Vec3<S> n = s0j * b.axis.cast<S>();
    const S* y = state.y + b.v_index;
    t.w = n * y[2];
    t.sd = s0j * (u1 * y[0] + u2 * y[1]);
    if constexpr (L == Level::kAcceleration) {
      const S* yd = state.yd + b.v_index;
      t.wd = n * yd[2];
      t.sdd = s0j * (u1 * yd[0] + u2 * yd[1]);
    }
  }
  body_update<L, true, true>(b, k, t, data);
}

#ifdef MBK_VEC4
// The revolute kernels of the AVX2 copy on four-lane vectors (vec4.h): the sums of the kernels
// above, term for term and in the same order, so the same results bit for bit, in fewer
// instructions.
namespace v4 {

// A point's position, velocity and acceleration, and a body's omega and alpha, in registers.
struct PointMotion {
  V4 p{}, v{}, a{};
};
struct BodySpin {
  V4 omega{}, alpha{};
};

// Where Data keeps a point's motion (the origins', or the mass centers').
struct PointArrays {
  Vec3<double>*p, *v, *a;
};

template <Level L>
MBK_AVX2 PointMotion load_point(const PointArrays& arrays, int k) {
  PointMotion m;
  m.p = load3(arrays.p[k].data());
  if constexpr (L != Level::kPose) m.v = load3(arrays.v[k].data());
  if constexpr (L == Level::kAcceleration) m.a = load3(arrays.a[k].data());
  return m;
}

template <Level L>
MBK_AVX2 void store_point(const PointArrays& arrays, int k, const PointMotion& m) {
  store3(arrays.p[k].data(), m.p);
  if constexpr (L != Level::kPose) store3(arrays.v[k].data(), m.v);
  if constexpr (L == Level::kAcceleration) store3(arrays.a[k].data(), m.a);
}

// Q = P + r fixed in a body of omega and alpha s (eq. 4.6.2 and its derivatives):
// Q' = P' + omega x r, Q'' = P'' + alpha x r + omega x (omega x r).
template <Level L>
MBK_AVX2 PointMotion carried(const PointMotion& p, const BodySpin& s, V4 r) {
  PointMotion q;
  q.p = p.p + r;
  if constexpr (L != Level::kPose) {
    const V4 omega_r = cross(s.omega, r);
    q.v = p.v + omega_r;
    if constexpr (L == Level::kAcceleration)
      q.a = (p.a + cross(s.alpha, r)) + cross(s.omega, omega_r);
  }
  return q;
}

// m v for a constant v of the given shape (times_constant above).
MBK_AVX2 inline V4 times_constant(const Cols& m, const Vec3<double>& v, VectorShape shape) {
  if (shape == VectorShape::kDense) return times(m, v.data());  // first: random offsets
  switch (shape) {
    case VectorShape::kZero:
      return V4{};
    case VectorShape::kX:
      return m.c0 * splat_at(v.data());
    case VectorShape::kY:
      return m.c1 * splat_at(v.data() + 1);
    case VectorShape::kZ:
      return m.c2 * splat_at(v.data() + 2);
    case VectorShape::kDense:
      break;
  }
  return times(m, v.data());
}

// omega_k = omega_j + w (eq. 4.4.6), alpha_k = alpha_j + wd + omega_j x w (eq. 4.5.1), with
// w = u q', wd = u q'': u = S0J w_k / q', the joint's axis in R; v: the joint's speed.
template <Level L>
MBK_AVX2 BodySpin turned_spin(const BodySpin& j, V4 u, const StateView<double>& state, int v) {
  BodySpin k;
  if constexpr (L != Level::kPose) {
    const V4 w = u * splat_at(state.y + v);
    k.omega = j.omega + w;
    if constexpr (L == Level::kAcceleration)
      k.alpha = (j.alpha + u * splat_at(state.yd + v)) + cross(j.omega, w);
  }
  return k;
}

// Stores S0K (reorthonormalized at its depth, body_update) and returns S0K r_k.
MBK_AVX2 inline V4 store_rotation(const BodyStep& b, int k, const Cols& s0k,
                                  const DataView<double>& data) {
  store_cols(data.rotation[k], s0k);
  if (!b.reorthonormalize) return times_constant(s0k, b.mass_center, b.mass_center_shape);
  reorthonormalize(data.rotation[k]);
  return times_constant(load_cols(data.rotation[k]), b.mass_center, b.mass_center_shape);
}

// Body k of a revolute joint (body_update): S0K, its spin from u (turned_spin), O_k = O_j +
// S0J q_k and G_k = O_k + S0K r_k with their motion (carried; r = 0 leaves the point's).
template <Level L>
MBK_AVX2 void revolute_update(const BodyStep& b, int k, const Cols& s0j, const Cols& s0k, V4 u,
                              const StateView<double>& state, const DataView<double>& data) {
  const int j = b.lower;
  const V4 rho = store_rotation(b, k, s0k, data);
  BodySpin spin_j;
  if constexpr (L != Level::kPose) spin_j.omega = load3(data.omega[j].data());
  if constexpr (L == Level::kAcceleration) spin_j.alpha = load3(data.alpha[j].data());
  const BodySpin spin_k = turned_spin<L>(spin_j, u, state, b.v_index);
  if constexpr (L != Level::kPose) store3(data.omega[k].data(), spin_k.omega);
  if constexpr (L == Level::kAcceleration) store3(data.alpha[k].data(), spin_k.alpha);
  const PointArrays origins{data.origin, data.origin_velocity, data.origin_acceleration};
  const PointArrays centers{data.mass_center, data.mass_center_velocity,
                            data.mass_center_acceleration};
  PointMotion point = load_point<L>(origins, j);
  if (b.offset_shape != VectorShape::kZero)
    point = carried<L>(point, spin_j, times_constant(s0j, b.offset, b.offset_shape));
  store_point<L>(origins, k, point);
  if (b.mass_center_shape != VectorShape::kZero) point = carried<L>(point, spin_k, rho);
  store_point<L>(centers, k, point);
}

// S0K = S0J SJK for a turn (cos, sin at c, s) about coordinate axis I (turn_columns).
template <int I>
MBK_AVX2 Cols turn_columns(const Cols& s0j, const double* c, const double* s) {
  constexpr int a = (I + 1) % 3, b = (I + 2) % 3;
  const V4 cos = splat_at(c), sin = splat_at(s);
  const V4 turned_a = cos * col<a>(s0j) + sin * col<b>(s0j);
  const V4 turned_b = cos * col<b>(s0j) - sin * col<a>(s0j);
  if constexpr (I == 0) return {s0j.c0, turned_a, turned_b};
  if constexpr (I == 1) return {turned_b, s0j.c1, turned_a};
  if constexpr (I == 2) return {turned_a, turned_b, s0j.c2};
}

// Column i of S0J SJK with SJK = P0 + c P1 + s P2 (folded_turn); p: P0 P1 P2 padded.
MBK_AVX2 inline V4 folded_column(const PaddedMat3* p, int i, const Cols& s0j, V4 cos, V4 sin) {
  const V4 sjk = (load4(p[0].col[i]) + cos * load4(p[1].col[i])) + sin * load4(p[2].col[i]);
  return times(s0j, sjk);
}

MBK_AVX2 inline Cols folded_turn(const PaddedMat3* p, const Cols& s0j, const double* c,
                                 const double* s) {
  const V4 cos = splat_at(c), sin = splat_at(s);
  return {folded_column(p, 0, s0j, cos, sin), folded_column(p, 1, s0j, cos, sin),
          folded_column(p, 2, s0j, cos, sin)};
}

// Revolute joint about coordinate axis I, C_k = I: u = column I of S0J.
template <Level L, int I>
MBK_AVX2 void revolute_axis_step(const BodyStep& b, int k, const StateView<double>& state,
                                 const DataView<double>& data) {
  const Cols s0j = load_cols(data.rotation[b.lower]);
  const Cols s0k = turn_columns<I>(s0j, data.cosine + b.angle, data.sine + b.angle);
  revolute_update<L>(b, k, s0j, s0k, col<I>(s0j), state, data);
}

// Revolute joint about any axis with any C_k: u = S0J (C_k a).
template <Level L>
MBK_AVX2 void revolute_step(const Model& model, const BodyStep& b, int k,
                            const StateView<double>& state, const DataView<double>& data) {
  const Cols s0j = load_cols(data.rotation[b.lower]);
  const Cols s0k = folded_turn(model.steps.padded.data() + b.matrices, s0j, data.cosine + b.angle,
                               data.sine + b.angle);
  const V4 u = L == Level::kPose ? V4{} : times(s0j, b.axis.data());
  revolute_update<L>(b, k, s0j, s0k, u, state, data);
}

}  // namespace v4
#endif  // MBK_VEC4

// Revolute joint about coordinate axis I, C_k = I: v4 for velocities and accelerations; the
// pose alone (two columns turned, a column or two added) takes fewer instructions in Eigen's
// code, which GCC vectorizes itself.
// kAvx2: in the AVX2 copy (double).
template <Level L, int I, bool kAvx2, typename S>
void axis_step(const BodyStep& b, int k, const StateView<S>& state, const DataView<S>& data) {
#ifdef MBK_VEC4
  if constexpr (kAvx2 && L != Level::kPose) {
    v4::revolute_axis_step<L, I>(b, k, state, data);
    return;
  }
#endif
  revolute_axis_step<L, I>(b, k, state, data);
}

// Revolute joint about any axis: v4, Eigen, or joint_motion (reference builds: kFolded).
template <Level L, bool kAvx2, typename S>
void any_axis_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                   const DataView<S>& data) {
#ifdef MBK_VEC4
  if constexpr (kAvx2) {
    v4::revolute_step<L>(model, b, k, state, data);
    return;
  }
#endif
  if constexpr (kFolded<S>)
    revolute_step<L>(model, b, k, state, data);
  else
    motion_step<L>(model, k, state, data);
}

// kAvx2: the AVX2 copy's (forward_kinematics_avx2), double only.
template <Level L, typename S, bool kAvx2 = false>
MBK_FLATTEN void forward_kinematics_at(const Model& model, const JointState<S>& joint_state,
                                       Data<S>& all) {
  const StateView<S> state(joint_state);
  angle_sines(model, state.q, all);
  const DataView<S> data(all);
  const int n = model.body_count();
  const BodyStep* steps = model.steps.steps.data();
  for (int k = 1; k <= n; ++k) {
    const BodyStep& b = steps[k];
    switch (b.kernel) {
      case JointKernel::kRevoluteX:
        axis_step<L, 0, kAvx2>(b, k, state, data);
        break;
      case JointKernel::kRevoluteY:
        axis_step<L, 1, kAvx2>(b, k, state, data);
        break;
      case JointKernel::kRevoluteZ:
        axis_step<L, 2, kAvx2>(b, k, state, data);
        break;
      case JointKernel::kRevolute:
        any_axis_step<L, kAvx2>(model, b, k, state, data);
        break;
      case JointKernel::kPrismatic:
        prismatic_step<L, false>(model, b, k, state, data);
        break;
      case JointKernel::kPrismaticRotated:
        if constexpr (kFolded<S>)
          prismatic_step<L, true>(model, b, k, state, data);
        else
          motion_step<L>(model, k, state, data);
        break;
      case JointKernel::kFixed:
        fixed_step<L, false>(model, b, k, state, data);
        break;
      case JointKernel::kFixedRotated:
        fixed_step<L, true>(model, b, k, state, data);
        break;
      case JointKernel::kBall123:
        ball_step<L, JointKernel::kBall123>(model, b, k, state, data);
        break;
      case JointKernel::kBallEuler:
        ball_step<L, JointKernel::kBallEuler>(model, b, k, state, data);
        break;
      case JointKernel::kFree123:
        ball_step<L, JointKernel::kFree123>(model, b, k, state, data);
        break;
      case JointKernel::kFreeEuler:
        ball_step<L, JointKernel::kFreeEuler>(model, b, k, state, data);
        break;
      case JointKernel::kBallOrdered:
        with_euler_order(b.euler_order, [&](auto o) {
          ball_step<L, JointKernel::kBall123, decltype(o)::value>(model, b, k, state, data);
        });
        break;
      case JointKernel::kFreeOrdered:
        with_euler_order(b.euler_order, [&](auto o) {
          ball_step<L, JointKernel::kFree123, decltype(o)::value>(model, b, k, state, data);
        });
        break;
      case JointKernel::kPlanar:
        if constexpr (kFolded<S>)
          planar_step<L>(model, b, k, state, data);
        else
          motion_step<L>(model, k, state, data);
        break;
      case JointKernel::kGeneric:
        motion_step<L>(model, k, state, data);
        break;
    }
  }
}

#ifdef MBK_AVX2_DISPATCH
template <Level L>
__attribute__((target("avx2"))) MBK_FLATTEN void forward_kinematics_avx2(
    const Model& model, const JointState<double>& state, Data<double>& data) {
  forward_kinematics_at<L, double, true>(model, state, data);
}

inline bool has_avx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}
#endif

// forward_kinematics_at, for AVX2 where it pays (MBK_AVX2_DISPATCH).
template <Level L, typename S>
void forward_kinematics_on_cpu(const Model& model, const JointState<S>& state, Data<S>& data) {
#ifdef MBK_AVX2_DISPATCH
  if constexpr (std::is_same_v<S, double>)
    if (has_avx2()) return forward_kinematics_avx2<L>(model, state, data);
#endif
  forward_kinematics_at<L>(model, state, data);
}

}  // namespace detail

// Computes, for every body k = 1..N in increasing order (so L(k) is done first), its
// orientation and origin, and with `level` its velocities and accelerations. No allocation.
template <typename S>
void forward_kinematics(const Model& model, const JointState<S>& state, Data<S>& data,
                        Level level = Level::kAcceleration) {
  assert(sized_for(data, model) && "forward_kinematics: Data made for another model");
  switch (level) {
    case Level::kPose:
      return detail::forward_kinematics_on_cpu<Level::kPose>(model, state, data);
    case Level::kVelocity:
      return detail::forward_kinematics_on_cpu<Level::kVelocity>(model, state, data);
    case Level::kAcceleration:
      return detail::forward_kinematics_on_cpu<Level::kAcceleration>(model, state, data);
  }
}

}  // namespace mbk
