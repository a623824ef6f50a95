// The human scene's update, N times, with every ball and free joint's angles in one Euler order:
// the driver that bench/euler_instructions.sh runs under callgrind (instructions per update, the
// difference of two counts: doc/speed.md "Euler orders").
//   euler_instructions ORDER recursive|pv pose|velocity|full N
#include <cstdio>
#include <stdexcept>
#include <string>

#include "bench/bench_scene.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/io/load_model.h"

namespace {

mbk::Level level_of(const std::string& name) {
  if (name == "pose") return mbk::Level::kPose;
  if (name == "velocity") return mbk::Level::kVelocity;
  if (name == "full") return mbk::Level::kAcceleration;
  throw std::invalid_argument("unknown level '" + name + "' (pose, velocity or full)");
}

mbk::Model human_in_order(mbk::EulerOrder order) {
  mbk::Model model = mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/config/human_body.yaml");
  for (mbk::Body& body : model.bodies)
    if (mbk::takes_euler_order(body.joint.type)) body.joint.euler_order = order;
  mbk::finalize_model(model);
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: euler_instructions ORDER recursive|pv pose|velocity|full N\n");
    return 2;
  }
  try {
    const mbk::Model model = human_in_order(mbk::euler_order_from_string(argv[1]));
    const std::string formulation = argv[2];
    const mbk::Level level = level_of(argv[3]);
    const long n = std::stol(argv[4]);
    if (formulation != "recursive" && formulation != "pv")
      throw std::invalid_argument("unknown formulation '" + formulation + "' (recursive or pv)");
    mbk::JointState<double> state = mbk_bench::random_state(model, 1);
    mbk::Data<double> data(model);
    mbk::PartialVelocities<double> pv(model);
    double sum = 0.0;  // read every result, so that no update is left out
    for (long i = 0; i < n; ++i) {
      mbk_bench::nudge(state.position.data(), state.velocity.data(), model.nq, i);
      if (formulation == "recursive")
        mbk::forward_kinematics(model, state, data, level);
      else
        mbk::partial_velocity_kinematics(model, state, pv, data, level);
      sum += data.origin.back().x() + data.mass_center_acceleration.back().x();
    }
    std::printf("%g\n", sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "euler_instructions: %s\n", e.what());
    return 2;
  }
  return 0;
}
