#include "mb_kinematics/core/kinematics_double4.h"

#include <stdexcept>

#include "mb_kinematics/core/kinematics.h"

namespace mbk {
namespace {

#ifdef MBK_AVX2_DISPATCH
template <Level L>
__attribute__((target("avx2"))) MBK_FLATTEN void lanes_kinematics_avx2(
    const Model& model, const JointState<Double4>& state, Data<Double4>& data) {
  detail::kinematics_loop<L, Double4>(model, state, data);
}

__attribute__((target("avx2"))) MBK_FLATTEN void lanes_system_avx2(const Model& model,
                                                                   const Data<Double4>& data,
                                                                   SystemKinematics<Double4>& out,
                                                                   Level level) {
  system_kinematics<Double4>(model, data, out, level);
}
#endif

void expect_four_samples(const Model& model) {
  if (!four_samples_at_once(model))
    throw std::logic_error("four samples at once: not for this model on this CPU");
}

}  // namespace

bool four_samples_at_once(const Model& model) {
#ifdef MBK_AVX2_DISPATCH
  static const bool avx2 = __builtin_cpu_supports("avx2");  // not has_avx2: ctest update_once
  return avx2 && !model.steps.generic;
#else
  (void)model;
  return false;
#endif
}

void forward_kinematics(const Model& model, const JointState<Double4>& state, Data<Double4>& data,
                        Level level) {
  expect_four_samples(model);
#ifdef MBK_AVX2_DISPATCH
  switch (level) {
    case Level::kPose:
      return lanes_kinematics_avx2<Level::kPose>(model, state, data);
    case Level::kVelocity:
      return lanes_kinematics_avx2<Level::kVelocity>(model, state, data);
    case Level::kAcceleration:
      return lanes_kinematics_avx2<Level::kAcceleration>(model, state, data);
  }
#endif
}

void system_kinematics(const Model& model, const Data<Double4>& data,
                       SystemKinematics<Double4>& out, Level level) {
  expect_four_samples(model);
#ifdef MBK_AVX2_DISPATCH
  lanes_system_avx2(model, data, out, level);
#endif
}

}  // namespace mbk
