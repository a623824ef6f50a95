// Absolute kinematics by the O(N) outward recursion along the lower body array (doc/method.md 4),
// as the method states it: for k = 1..N in increasing order (so L(k) = j is done first), body k
// from body j and its joint's terms (JointTerms) by body_update; the generic step (motion_step)
// takes any joint's terms from joint_motion; forward_kinematics is the entry point.
// Each body runs its joint's kernel, chosen once when the model was finalized (body_step.h): the
// generic step, or a fast kernel (fast_kernels.h) that gets the same terms with fewer operations
// and runs the same body_update (test/core/generic_kernel_test.cc checks one against the other).
#pragma once

#include <cassert>
#include <limits>
#include <type_traits>

#include "mb_kinematics/core/body_step.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/kinematics_views.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {
namespace detail {

// A joint's share of body k's motion, in R components: d = S0J (q_k + s_k) (O_j to O_k), the
// relative angular velocity w = S0J w_k and w' part wd = S0J w_k', and sd = S0J s_k',
// sdd = S0J s_k''.
template <typename S>
struct JointTerms {
  Vec3<S> d, w, wd, sd, sdd;
};

// O_k and its velocity and acceleration from O_j's (doc/method.md 4, eq. 4.6.2): O_k is the point
// at d of Bj, moved by S0J s_k' (and its Coriolis term) when the joint translates; d = 0 (a joint
// at O_j that does not translate) leaves them O_j's.
template <Level L, bool kTranslates, typename S>
void origin_update(const BodyStep& b, int k, const JointTerms<S>& t, const DataView<S>& data) {
  const int j = b.lower;
  const PointArrays<S> origins = data.origins();
  if (!kTranslates && b.offset_shape == VectorShape::kZero)
    return set_point<L>(origins, k, point_at<L>(origins, j));
  PointMotion<Vec3<S>> o =
      fixed_point<L>(point_at<L>(origins, j), data.omega[j], data.alpha[j], t.d);
  if constexpr (kTranslates && L != Level::kPose) {
    o.velocity += t.sd;                       // doc/method.md 4, origin velocity
    if constexpr (L == Level::kAcceleration)  // doc/method.md 4, origin acceleration
      o.acceleration += S(2) * data.omega[j].cross(t.sd) + t.sdd;
  }
  set_point<L>(origins, k, o);
}

// G_k and its velocity and acceleration from O_k's, rho = S0K r_k (doc/method.md 4, mass
// center): r_k = 0 leaves them O_k's.
template <Level L, typename S>
void mass_center_update(const BodyStep& b, int k, const DataView<S>& data) {
  const PointMotion<Vec3<S>> o = point_at<L>(data.origins(), k);
  if (b.mass_center_shape == VectorShape::kZero) return set_point<L>(data.centers(), k, o);
  const Vec3<S> rho = times_constant(data.rotation[k], b.mass_center, b.mass_center_shape);
  set_point<L>(data.centers(), k, fixed_point<L>(o, data.omega[k], data.alpha[k], rho));
}

// Body k from its lower body once S0K = S0J SJK is in data.rotation[k] (doc/method.md 4).
// kRotates, kTranslates: whether the joint turns (w, wd used) and translates (sd, sdd used).
template <Level L, bool kRotates, bool kTranslates, typename S>
void body_update(const BodyStep& b, int k, const JointTerms<S>& t, const DataView<S>& data) {
  const int j = b.lower;
  if (b.reorthonormalize) reorthonormalize(data.rotation[k]);  // doc/method.md 4, orientation
  if constexpr (L != Level::kPose) {
    const Vec3<S>& omega_j = data.omega[j];
    Vec3<S>& omega_k = data.omega[k];
    omega_k = omega_j;
    if constexpr (kRotates) omega_k += t.w;  // doc/method.md 4, eq. 4.4.6
    if constexpr (L == Level::kAcceleration) {
      if constexpr (kRotates)
        data.alpha[k] = data.alpha[j] + t.wd + omega_j.cross(t.w);  // doc/method.md 4, eq. 4.5.1
      else
        data.alpha[k] = data.alpha[j];
    }
  }
  origin_update<L, kTranslates>(b, k, t, data);
  mass_center_update<L>(b, k, data);
}

// Any joint from its joint_motion.
template <typename S>
void motion_pose(const BodyStep& b, int k, const JointMotion<S>& m, const DataView<S>& data,
                 Vec3<S>& d) {
  const Mat3<S>& s0j = data.rotation[b.lower];
  data.rotation[k] = s0j * m.rotation;             // doc/method.md 4, S0K = S0J SJK
  d = s0j * (b.offset.cast<S>() + m.translation);  // doc/method.md 4, eq. 4.6.2: d_k
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
    body_update<L, true, true>(b, k, t, data);
  else
    body_update<L, true, false>(b, k, t, data);
}

// Body k by its joint's kernel: fast_kernels.h, included at the end of this file.
template <Level L, bool kAvx2, typename S>
void kernel_step(const Model& model, const BodyStep& b, int k, const StateView<S>& state,
                 const DataView<S>& data);

// The loop over bodies. kAvx2: the AVX2 copy's (forward_kinematics_avx2), double only.
template <Level L, typename S, bool kAvx2 = false>
void kinematics_loop(const Model& model, const JointState<S>& joint_state, Data<S>& all) {
  const StateView<S> state(joint_state);
  angle_sines(model, state.q, all);
  const DataView<S> data(all);
  const int n = model.body_count();
  const BodyStep* steps = model.steps.steps.data();
  for (int k = 1; k <= n; ++k) kernel_step<L, kAvx2>(model, steps[k], k, state, data);
}

// Whether the loop gets every step inlined into it (MBK_FLATTEN): in double and float, not in the
// wider types of the references (analysis/reference_kinematics.h). There the arithmetic is the
// time (x87 in long double, a libquadmath call per operation in quad precision): flattened, the
// long double loop ran as fast (0.87 s for 40,000 updates of a 50-body tree either way), and GCC
// at -O3 took 35 CPU s for its file against 6.5, 73 for the quad one against 7.4.
template <typename S>
constexpr bool kFlattened = std::numeric_limits<S>::digits <= std::numeric_limits<double>::digits;

// The loop with every step inlined into it.
template <Level L, typename S, bool kAvx2 = false>
MBK_FLATTEN void forward_kinematics_at(const Model& model, const JointState<S>& state,
                                       Data<S>& data) {
  kinematics_loop<L, S, kAvx2>(model, state, data);
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

// forward_kinematics_at, for AVX2 where it pays (MBK_AVX2_DISPATCH); the loop alone in long
// double and quad precision (kFlattened).
template <Level L, typename S>
void forward_kinematics_on_cpu(const Model& model, const JointState<S>& state, Data<S>& data) {
  if constexpr (!kFlattened<S>) {
    kinematics_loop<L>(model, state, data);
  } else {
#ifdef MBK_AVX2_DISPATCH
    if constexpr (std::is_same_v<S, double>)
      if (has_avx2()) return forward_kinematics_avx2<L>(model, state, data);
#endif
    forward_kinematics_at<L>(model, state, data);
  }
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

// kernel_step, and the kernels it runs (they call body_update and motion_step above).
#include "mb_kinematics/core/fast_kernels.h"
