// The joints' kernels of the recursion: for body k, its joint's share (JointTerms: S0K into
// data.rotation[k], d, S0J w_k, S0J w_k', S0J s_k', S0J s_k''), then the one-body update
// (body_update.h). with_kernel is the one table over JointKernel (chosen for each body when the
// model is finalized: body_step.cc kernel_of), joint_terms each kernel's terms; kernel_step runs
// them for the recursion, pose_step gives their pose part to partial_velocity_kinematics.
// The generic kernel (motion_step) takes any joint's terms from joint_motion's SJK, W_r and s_k
// and full 3x3 products. The fast ones get the same terms with fewer operations: a revolute joint
// about x, y or z turns two columns of S0J (a ball or free joint's angles three column turns, in
// any Euler order), C_k and the axis are folded into constants at load (P0 + cos q P1 + sin q P2),
// and S0J w_k is a column of S0J, so the update does neither joint_motion nor SJK (doc/speed.md,
// "How the update is fast"). On AVX2 CPUs the revolute joints' terms are four-lane vectors
// (fast_kernels_avx2.h), and body_update runs on them.
// How they are checked: test/core/generic_kernel_test.cc runs every joint type, with and without
// offset rotations, through its kernel and through the generic path
// (make_body_steps(model, KernelChoice::kGenericOnly)), at every level and in both formulations,
// and requires the same results to rounding; the forward_kinematics it calls is the AVX2 copy on
// AVX2 CPUs, so the copy is checked the same way.
#pragma once

#include <array>
#include <limits>
#include <type_traits>

#include "mb_kinematics/core/body_update.h"
#include "mb_kinematics/core/fast_kernels_avx2.h"
#include "mb_kinematics/core/joint_motion.h"

namespace mbk {
namespace detail {

// Any joint from its joint_motion m: S0K and d.
template <typename S>
void motion_pose(const BodyStep& b, int k, const JointMotion<S>& m, const DataView<S>& data,
                 Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  data.rotation[k] = s0j * m.rotation;             // doc/method.md 4, S0K = S0J SJK
  d = s0j * (b.offset.cast<S>() + m.translation);  // doc/method.md 4, eq. 4.6.2: d_k
}

// Any joint through joint_motion, column by column: the generic kernel (JointKernel::kGeneric),
// and the folded joints of a reference build.
template <Level L, typename S>
void motion_step(const Model& model, int k, const StateView<S>& state, const DataView<S>& data) {
  const Body& body = model.bodies[k];
  const BodyStep& b = model.steps.steps[k];
  const S* y = L == Level::kPose ? nullptr : state.y + body.v_index;
  JointMotion<S> m;
  joint_motion(body.joint, model.speeds, state.q + body.q_index, y, m);
  JointTerms<Vec3<S>> t;
  motion_pose(b, k, m, data, t.d);
  const Mat3<S>& s0j = data.rotation[b.lower];
  if constexpr (L != Level::kPose) {
    Vec3<S> w = Vec3<S>::Zero(), sd = Vec3<S>::Zero();  // doc/method.md 4: w_k, s_k' in Bj
    for (int c = m.linear_speeds; c < m.speeds; ++c) w += m.angular[c] * y[c];
    for (int c = 0; c < m.linear_speeds; ++c) sd += m.linear[c] * y[c];
    t.w = s0j * w;
    t.sd = s0j * sd;
    if constexpr (L == Level::kAcceleration) {
      const S* yd = state.yd + body.v_index;
      Vec3<S> wd = Vec3<S>::Zero(), sdd = Vec3<S>::Zero();  // doc/method.md 4: w_k', s_k''
      for (int c = m.linear_speeds; c < m.speeds; ++c)
        wd += m.angular[c] * yd[c] + m.angular_dot[c] * y[c];
      for (int c = 0; c < m.linear_speeds; ++c) sdd += m.linear[c] * yd[c];
      t.wd = s0j * wd;
      t.sdd = s0j * sdd;
    }
  }
  if (m.linear_speeds > 0)  // the s_k' terms vanish otherwise
    body_update<L, JointMoves::kTurnsAndTranslates>(b, k, t, data);
  else
    body_update<L, JointMoves::kTurns>(b, k, t, data);
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
  s0k = product<S>(s0j, sjk);
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
  d = product<S>(s0j,
                 b.offset.cast<S>() + p[3].col(0).cast<S>() * x[0] + p[3].col(1).cast<S>() * x[1]);
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
    f.m = product<S>(s0j, model.steps.matrices[b.matrices].cast<S>());  // C_k
  else
    f.m = s0j;
  if constexpr (kAngles<K>)
    angles_pose<O>(data.cosine + b.angle, data.sine + b.angle, f, data.rotation[k]);
  else
    data.rotation[k] = product<S>(f.m, rotation_euler(angles));
  d = times_constant(s0j, b.offset, b.offset_shape);
  if constexpr (kFreeJoint<K>) d += product<S>(f.m, Vec3<S>(x[0], x[1], x[2]));
}

// Prismatic (kTranslates) or fixed joint: SJK = C_k (I when not kRotated), s_k = (C_k a) q.
template <bool kRotated, bool kTranslates, typename S>
void rigid_pose(const Model& model, const BodyStep& b, int k, const S* q, const DataView<S>& data,
                Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  if constexpr (kRotated)
    data.rotation[k] = product<S>(s0j, model.steps.matrices[b.matrices].cast<S>());
  else
    data.rotation[k] = s0j;
  if constexpr (kTranslates)
    d = product<S>(s0j, b.offset.cast<S>() + b.axis.cast<S>() * q[b.q_index]);
  else
    d = times_constant(s0j, b.offset, b.offset_shape);
}

// Constants folded in double (P0 P1 P2, C_k a, the plane's axes) serve double and float;
// wider reference builds take those joints through joint_motion, on the model's own C_k and axis.
template <typename S>
constexpr bool kFolded = std::numeric_limits<S>::digits <= std::numeric_limits<double>::digits;

// Whether body k's kernel runs through joint_motion.
template <typename S>
constexpr bool uses_joint_motion(JointKernel kernel) {
  return kernel == JointKernel::kGeneric ||
         (!kFolded<S> &&
          (kernel == JointKernel::kRevolute || kernel == JointKernel::kPrismaticRotated ||
           kernel == JointKernel::kPlanar));
}

// Revolute joint about coordinate axis I, C_k = I: w_k = e_I q', so S0J w_k = column I of S0J q'.
template <Level L, int I, typename S>
void axis_terms(const BodyStep& b, int k, const StateView<S>& state, const DataView<S>& data,
                JointTerms<Vec3<S>>& t) {
  axis_pose<I>(b, k, data, t.d);
  const Mat3<S>& s0j = data.rotation[b.lower];
  if constexpr (L != Level::kPose) t.w = s0j.col(I) * state.y[b.v_index];
  if constexpr (L == Level::kAcceleration) t.wd = s0j.col(I) * state.yd[b.v_index];
}

// Revolute joint about any axis: S0J w_k = S0J (C_k a) q'.
template <Level L, typename S>
void revolute_terms(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                    const DataView<S>& data, JointTerms<Vec3<S>>& t) {
  revolute_pose(model, b, k, data, t.d);
  if constexpr (L != Level::kPose) {
    const Vec3<S> u = product<S>(data.rotation[b.lower], b.axis.cast<S>());
    t.w = u * state.y[b.v_index];
    if constexpr (L == Level::kAcceleration) t.wd = u * state.yd[b.v_index];
  }
}

// Prismatic joint: s_k' = (C_k a) q'.
template <Level L, bool kRotated, typename S>
void prismatic_terms(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                     const DataView<S>& data, JointTerms<Vec3<S>>& t) {
  rigid_pose<kRotated, true>(model, b, k, state.q, data, t.d);
  if constexpr (L != Level::kPose) {
    const Vec3<S> u = product<S>(data.rotation[b.lower], b.axis.cast<S>());
    t.sd = u * state.y[b.v_index];
    if constexpr (L == Level::kAcceleration) t.sdd = u * state.yd[b.v_index];
  }
}

// w_k and the w_k' part of angles in the order O in R (eq. 4.4.13-4.4.16 for 1-2-3): the
// columns e_a1, R_a1 e_a2, R_a1 R_a2 e_a3 carried by M are u0 = M e_a1, u1 = (M R_a1) e_a2,
// u2 = (M R_a1 R_a2) e_a3, and their rates (eq. 4.5; R_a' = R_a [e_a]x angle') are
// u1' = alpha' (M R_a1) (e_a1 x e_a2) = sigma alpha' (M R_a1) e_third and u2' = kappa alpha' u1 +
// beta' (M R_a1 R_a2) (e_a2 x e_a3), e_a2 x e_a3 = sigma e_a1 (Tait-Bryan) or -sigma e_third
// (proper Euler); linear in M, as C_k (angular_dot) carries them in joint_motion. Each sign is a
// constant: a sum or a difference.
template <Level L, EulerOrder O, typename S>
void angles_rates(const BallFrame<S>& f, const S* y, const S* yd, JointTerms<Vec3<S>>& t) {
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
void ball_terms(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                const DataView<S>& data, JointTerms<Vec3<S>>& t, BallFrame<S>& f) {
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
      t.w = product<S>(f.m, w);
      if constexpr (L == Level::kAcceleration) t.wd = product<S>(f.m, wd);
    }
    if constexpr (kFreeJoint<K>) {
      t.sd = product<S>(f.m, Vec3<S>(y[0], y[1], y[2]));
      if constexpr (L == Level::kAcceleration)
        t.sdd = product<S>(f.m, Vec3<S>(yd[0], yd[1], yd[2]));
    }
  }
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
void planar_terms(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                  const DataView<S>& data, JointTerms<Vec3<S>>& t) {
  planar_pose(model, b, k, state.q, data, t.d);
  if constexpr (L != Level::kPose) {
    const Mat3<S>& s0j = data.rotation[b.lower];
    const Vec3<S> u1 = model.steps.matrices[b.matrices + 3].col(0).cast<S>();
    const Vec3<S> u2 = model.steps.matrices[b.matrices + 3].col(1).cast<S>();
    const Vec3<S> n = product<S>(s0j, b.axis.cast<S>());
    const S* y = state.y + b.v_index;
    t.w = n * y[2];
    t.sd = product<S>(s0j, u1 * y[0] + u2 * y[1]);
    if constexpr (L == Level::kAcceleration) {
      const S* yd = state.yd + b.v_index;
      t.wd = n * yd[2];
      t.sdd = product<S>(s0j, u1 * yd[0] + u2 * yd[1]);
    }
  }
}

// The one table over JointKernel (body_step.h): f(kernel) with body k's kernel as a compile-time
// constant (std::integral_constant), for the recursion (kernel_step) and the partial velocities'
// pose (pose_step).
template <typename F>
void with_kernel(JointKernel kernel, F&& f) {
  using K = JointKernel;
  switch (kernel) {
    case K::kFixed:
      return f(std::integral_constant<K, K::kFixed>{});
    case K::kFixedRotated:
      return f(std::integral_constant<K, K::kFixedRotated>{});
    case K::kRevoluteX:
      return f(std::integral_constant<K, K::kRevoluteX>{});
    case K::kRevoluteY:
      return f(std::integral_constant<K, K::kRevoluteY>{});
    case K::kRevoluteZ:
      return f(std::integral_constant<K, K::kRevoluteZ>{});
    case K::kRevolute:
      return f(std::integral_constant<K, K::kRevolute>{});
    case K::kPrismatic:
      return f(std::integral_constant<K, K::kPrismatic>{});
    case K::kPrismaticRotated:
      return f(std::integral_constant<K, K::kPrismaticRotated>{});
    case K::kBall123:
      return f(std::integral_constant<K, K::kBall123>{});
    case K::kBallEuler:
      return f(std::integral_constant<K, K::kBallEuler>{});
    case K::kFree123:
      return f(std::integral_constant<K, K::kFree123>{});
    case K::kFreeEuler:
      return f(std::integral_constant<K, K::kFreeEuler>{});
    case K::kBallOrdered:
      return f(std::integral_constant<K, K::kBallOrdered>{});
    case K::kFreeOrdered:
      return f(std::integral_constant<K, K::kFreeOrdered>{});
    case K::kPlanar:
      return f(std::integral_constant<K, K::kPlanar>{});
    case K::kGeneric:
      return f(std::integral_constant<K, K::kGeneric>{});
  }
}

// What the joint of kernel K moves (body_update).
template <JointKernel K>
constexpr JointMoves kMoves =
    K == JointKernel::kFixed || K == JointKernel::kFixedRotated           ? JointMoves::kNone
    : K == JointKernel::kPrismatic || K == JointKernel::kPrismaticRotated ? JointMoves::kTranslates
    : kFreeJoint<K> || K == JointKernel::kPlanar ? JointMoves::kTurnsAndTranslates
                                                 : JointMoves::kTurns;

// The joint's terms of body k by its kernel K (not the generic one: motion_step), at level L; at
// Level::kPose, S0K and d alone (and a ball or free joint's frames f).
template <Level L, JointKernel K, typename S>
void joint_terms(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                 const DataView<S>& data, JointTerms<Vec3<S>>& t, BallFrame<S>& f) {
  using JK = JointKernel;
  if constexpr (K == JK::kRevoluteX || K == JK::kRevoluteY || K == JK::kRevoluteZ)
    axis_terms<L, kAxis<K>>(b, k, state, data, t);
  else if constexpr (K == JK::kRevolute)
    revolute_terms<L>(model, b, k, state, data, t);
  else if constexpr (K == JK::kPrismatic || K == JK::kPrismaticRotated)
    prismatic_terms<L, K == JK::kPrismaticRotated>(model, b, k, state, data, t);
  else if constexpr (K == JK::kFixed || K == JK::kFixedRotated)
    rigid_pose<K == JK::kFixedRotated, false>(model, b, k, state.q, data, t.d);
  else if constexpr (K == JK::kBallOrdered || K == JK::kFreeOrdered)
    with_euler_order(b.euler_order, [&](auto o) {
      constexpr JK kAngles123 = K == JK::kBallOrdered ? JK::kBall123 : JK::kFree123;
      ball_terms<L, kAngles123, decltype(o)::value>(model, b, k, state, data, t, f);
    });
  else if constexpr (K == JK::kPlanar)
    planar_terms<L>(model, b, k, state, data, t);
  else
    ball_terms<L, K>(model, b, k, state, data, t, f);
}

// Whether the AVX2 copy runs kernel K at level L on four-lane vectors (fast_kernels_avx2.h): the
// revolute joints at velocity and acceleration level, and at every level those about any axis; the
// pose alone of one about a coordinate axis (two columns turned, a column or two added) takes fewer
// instructions in Eigen's code, which GCC vectorizes itself.
template <Level L, JointKernel K>
constexpr bool kFourLanes = K == JointKernel::kRevolute ||
                            (L != Level::kPose &&
                             (K == JointKernel::kRevoluteX || K == JointKernel::kRevoluteY ||
                              K == JointKernel::kRevoluteZ));

// Body k by its joint's kernel: the joint's terms, then body_update with what the joint moves. The
// generic kernel (motion_step) serves kGeneric and, in reference builds (not kFolded), the joints
// whose constants are folded in double. kAvx2: the AVX2 copy (double only), whose revolute joints'
// terms are four-lane vectors (kFourLanes).
template <Level L, bool kAvx2, typename S>
void kernel_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                 const DataView<S>& data) {
  with_kernel(b.kernel, [&](auto kernel) {
    constexpr JointKernel K = decltype(kernel)::value;
    if constexpr (uses_joint_motion<S>(K) && kLanes<S>) {
      __builtin_unreachable();  // models with a generic kernel do not run on lanes
    } else if constexpr (uses_joint_motion<S>(K)) {
      motion_step<L>(model, k, state, data);
    } else if constexpr (kAvx2 && kFourLanes<L, K>) {
      v4::revolute_step<L, K>(model, b, k, state, data);
    } else {
      JointTerms<Vec3<S>> t;
      BallFrame<S> f;
      joint_terms<L, K>(model, b, k, state, data, t, f);
      body_update<L, kMoves<K>>(b, k, t, data);
    }
  });
}

// Orientation, origin and mass center of body k by its kernel (m: its joint_motion, used when
// uses_joint_motion); also returns d = S0J (q_k + s_k), rho = S0K r_k and, for ball and free
// joints, their frames f. For partial_velocity_kinematics: the pose part of kernel_step's.
template <typename S>
MBK_FLATTEN void pose_step(const Model& model, int k, const S* q, const JointMotion<S>& m,
                           Data<S>& all, Vec3<S>& d, Vec3<S>& rho, BallFrame<S>& f) {
  const DataView<S> data(all);
  const BodyStep& b = model.steps.steps[k];
  if (uses_joint_motion<S>(b.kernel)) {
    motion_pose(b, k, m, data, d);
  } else {
    with_kernel(b.kernel, [&](auto kernel) {
      constexpr JointKernel K = decltype(kernel)::value;
      if constexpr (!uses_joint_motion<S>(K)) {
        JointTerms<Vec3<S>> t;
        joint_terms<Level::kPose, K>(model, b, k, StateView<S>(q), data, t, f);
        d = t.d;
      }
    });
  }
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);
  data.origin[k] = data.origin[j] + d;                                         // eq. 4.6.2
  rho = times_constant(data.rotation[k], b.mass_center, b.mass_center_shape);  // S0K r_k
  data.mass_center[k] = data.origin[k] + rho;
}

}  // namespace detail
}  // namespace mbk
