#include "mb_kinematics/core/kinematics_lanes.h"

#include <stdexcept>
#include <string>

#include "mb_kinematics/core/kinematics.h"

namespace mbk {
namespace {

// Each lanes' count compiled for the least instruction set that has its vectors, every step
// inlined. The build's -ffp-contract=off keeps AVX-512F's fused multiply-adds out.
#ifdef MBK_AVX2_DISPATCH
template <Level L>
__attribute__((target("avx2"))) MBK_FLATTEN void lanes_kinematics(const Model& model,
                                                                  const JointState<Double4>& state,
                                                                  Data<Double4>& data) {
  detail::kinematics_loop<L, Double4>(model, state, data);
}

template <Level L>
__attribute__((target("avx512f"))) MBK_FLATTEN void lanes_kinematics(
    const Model& model, const JointState<Double8>& state, Data<Double8>& data) {
  detail::kinematics_loop<L, Double8>(model, state, data);
}

__attribute__((target("avx2"))) MBK_FLATTEN void lanes_system(const Model& model,
                                                              const Data<Double4>& data,
                                                              SystemKinematics<Double4>& out,
                                                              Level level) {
  system_kinematics<Double4>(model, data, out, level);
}

__attribute__((target("avx512f"))) MBK_FLATTEN void lanes_system(const Model& model,
                                                                 const Data<Double8>& data,
                                                                 SystemKinematics<Double8>& out,
                                                                 Level level) {
  system_kinematics<Double8>(model, data, out, level);
}
#endif

void expect_lanes(const Model& model, int lanes) {
  if (samples_at_once(model) < lanes)
    throw std::logic_error(std::to_string(lanes) +
                           " samples at once: not for this model on this CPU");
}

template <int N>
void kinematics_of_lanes(const Model& model, const JointState<DoubleLanes<N>>& state,
                         Data<DoubleLanes<N>>& data, Level level) {
  expect_lanes(model, N);
#ifdef MBK_AVX2_DISPATCH
  switch (level) {
    case Level::kPose:
      return lanes_kinematics<Level::kPose>(model, state, data);
    case Level::kVelocity:
      return lanes_kinematics<Level::kVelocity>(model, state, data);
    case Level::kAcceleration:
      return lanes_kinematics<Level::kAcceleration>(model, state, data);
  }
#endif
}

template <int N>
void system_of_lanes(const Model& model, const Data<DoubleLanes<N>>& data,
                     SystemKinematics<DoubleLanes<N>>& out, Level level) {
  expect_lanes(model, N);
#ifdef MBK_AVX2_DISPATCH
  lanes_system(model, data, out, level);
#endif
}

}  // namespace

int samples_at_once(const Model& model) {
#ifdef MBK_AVX2_DISPATCH
  // Not has_avx2: ctest update_once wants its guard in kinematics_double.cc's object alone.
  static const int lanes = __builtin_cpu_supports("avx512f") ? 8
                           : __builtin_cpu_supports("avx2")  ? 4
                                                             : 1;
  return model.steps.generic ? 1 : lanes;
#else
  (void)model;
  return 1;
#endif
}

void forward_kinematics(const Model& model, const JointState<Double4>& state, Data<Double4>& data,
                        Level level) {
  kinematics_of_lanes(model, state, data, level);
}

void forward_kinematics(const Model& model, const JointState<Double8>& state, Data<Double8>& data,
                        Level level) {
  kinematics_of_lanes(model, state, data, level);
}

void system_kinematics(const Model& model, const Data<Double4>& data,
                       SystemKinematics<Double4>& out, Level level) {
  system_of_lanes(model, data, out, level);
}

void system_kinematics(const Model& model, const Data<Double8>& data,
                       SystemKinematics<Double8>& out, Level level) {
  system_of_lanes(model, data, out, level);
}

}  // namespace mbk
