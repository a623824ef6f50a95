// Absolute kinematics by the O(N) outward recursion along the lower body array (doc/method.md 4),
// as the method states it: for k = 1..N in increasing order (so L(k) = j is done first), body k
// from body j by its joint's kernel (fast_kernels.h kernel_step: the joint's terms, then the
// one-body update of body_update.h). forward_kinematics is the entry point: it chooses, once per
// call, the level and the copy of the loop for the scalar and the CPU.
#pragma once

#include <cassert>
#include <limits>
#include <type_traits>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/fast_kernels.h"
#include "mb_kinematics/core/kinematics_views.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {
namespace detail {

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
