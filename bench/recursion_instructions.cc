// N updates of a scene of kinematics_benchmark, by the recursion or the partial velocities: the
// driver that bench/recursion_instructions.sh runs under callgrind (instructions per update, the
// difference of two counts: doc/speed.md "Instructions per update").
//   recursion_instructions SCENE recursive|pv pose|velocity|full N
// SCENE: human (config/human_body.yaml), human_urdf (config/human_body.urdf), humanoid29 and
// random64 (kinematics_benchmark's, through URDF text), tree100 (make_random_tree(100, 3): every
// joint type), chainN (make_chain(N, revolute)), human:ORDER (human with every ball and free
// joint's angles in an Euler order such as ZYX: bench/euler_instructions.sh).
#include <cstdio>
#include <stdexcept>
#include <string>

#include "bench/bench_scene.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"

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

mbk::Model scene(const std::string& name) {
  const std::string config = std::string(MBK_SOURCE_DIR) + "/config/";
  if (name == "human") return mbk::load_model_file(config + "human_body.yaml");
  if (name.rfind("human:", 0) == 0)
    return human_in_order(mbk::euler_order_from_string(name.substr(6)));
  if (name == "human_urdf") return mbk::load_model_file(config + "human_body.urdf");
  if (name == "humanoid29")
    return mbk::load_urdf_string(mbk::write_urdf(mbk_bench::humanoid29(), name), name);
  if (name == "random64")
    return mbk::load_urdf_string(mbk::write_urdf(mbk::make_random_revolute_tree(64, 7), name),
                                 name);
  if (name == "tree100") return mbk::make_random_tree(100, 3);
  if (name.rfind("chain", 0) == 0 && name.size() > 5)
    return mbk::make_chain(std::stoi(name.substr(5)), mbk::JointType::kRevolute);
  throw std::invalid_argument("unknown scene '" + name +
                              "' (human, human:ORDER, human_urdf, humanoid29, random64, tree100, chainN)");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: recursion_instructions SCENE recursive|pv pose|velocity|full N\n");
    return 2;
  }
  try {
    const mbk::Model model = scene(argv[1]);
    const std::string formulation = argv[2];
    const mbk::Level level = level_of(argv[3]);
    const long n = std::stol(argv[4]);
    if (formulation != "recursive" && formulation != "pv")
      throw std::invalid_argument("unknown formulation '" + formulation + "' (recursive or pv)");
    const bool recursive = formulation == "recursive";
    mbk::JointState<double> state = mbk_bench::random_state(model, 1);
    mbk::Data<double> data(model);
    mbk::PartialVelocities<double> pv(model);
    double sum = 0.0;  // read every result, so that no update is left out
    for (long i = 0; i < n; ++i) {
      mbk_bench::nudge(state.position.data(), state.velocity.data(), model.nq, i);
      if (recursive)
        mbk::forward_kinematics(model, state, data, level);
      else
        mbk::partial_velocity_kinematics(model, state, pv, data, level);
      sum += data.origin.back().x() + data.mass_center_acceleration.back().x();
    }
    std::printf("%g\n", sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "recursion_instructions: %s\n", e.what());
    return 2;
  }
  return 0;
}
