// libFuzzer harness: the node's JointState input adapter (mb_kinematics/ros/joint_state_input.h)
// on a stream of messages built from the fuzzer's bytes, for the human body URDF: names of the
// model's coordinates or others, duplicates, unequal lengths, NaN/Inf, huge and tiny values,
// stamps that repeat, go backwards or jump. Only the adapter's public add(msg, t) and fill(...)
// are used (and its constructor). Every sample it accepts and fills, when check_state accepts
// it, must evaluate without a crash or a sanitizer report.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/ros/joint_state_input.h"
#include "test/fuzz/fuzz_support.h"

namespace {

double value(FuzzedDataProvider& in) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double special[] = {0.0,  -0.0,  1e-310,  0.5,  -1.0,  3.14159,     1e50,
                            1e51, 1e300, 1.7e308, kInf, -kInf, std::nan("")};
  if (in.ConsumeBool()) return in.PickValueInArray(special);
  return in.ConsumeFloatingPoint<double>();
}

sensor_msgs::JointState message(FuzzedDataProvider& in, const mbk::Model& model) {
  sensor_msgs::JointState msg;
  const size_t n = in.ConsumeIntegralInRange<size_t>(0, model.nq + 2);
  for (size_t i = 0; i < n; ++i)
    msg.name.push_back(in.ConsumeBool() ? in.ConsumeRandomLengthString(12)
                                        : model.coordinate_names[in.ConsumeIntegralInRange<size_t>(
                                              0, model.coordinate_names.size() - 1)]);
  const size_t positions = in.ConsumeBool() ? n : in.ConsumeIntegralInRange<size_t>(0, n + 1);
  for (size_t i = 0; i < positions; ++i) msg.position.push_back(value(in));
  const size_t velocities = in.PickValueInArray({size_t{0}, n, n + 1});
  for (size_t i = 0; i < velocities; ++i) msg.velocity.push_back(value(in));
  return msg;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mbk::Model model =
      mbk::load_model_file(mbk_fuzz::source_path("config/human_body.urdf"));
  FuzzedDataProvider in(data, size);
  const std::string estimator = in.PickValueInArray(
      {"kalman_smooth", "kalman", "backward_difference", "savitzky_golay_end_7_2"});
  mbk_ros::JointStateInput input(model, *mbk::make_derivative_estimator(estimator),
                                 in.PickValueInArray({0.0, 1.0}));
  mbk::JointState<double> state(model);
  double t = 0;
  while (in.remaining_bytes() > 0) {
    const int step = in.ConsumeIntegralInRange<int>(0, 5);
    t = step == 0 ? t : step == 1 ? t - 1 : step == 2 ? 0.0 : step == 3 ? t + 1e6 : t + 1e-3;
    input.add(message(in, model), t);
    const auto level =
        in.PickValueInArray({mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration});
    if (input.fill(level, nullptr, state) == level)
      mbk_fuzz::expect_finite_kinematics(model, state);
  }
  return 0;
}
