// mbk_work_precision: error against run time for every method (issue "Error against run time").
// Writes <out>/work_precision.csv and <out>/work_precision.md; scripts/work_precision.sh runs it
// and plots the CSV. Error: see mb_kinematics/analysis/kinematics_error.h; reference: the same
// recursion in quad precision (boost float128) on the method's own inputs.
//   mbk_work_precision [--out DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/estimator_study.h"
#include "mb_kinematics/analysis/kinematics_error.h"
#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/analysis/quad.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/io/load_model.h"

namespace mbk {
namespace {

struct Row {
  std::string method, scene;
  double median_ns, min_ns, max_ns, error;
  std::string note;
};

struct Timing {
  double median, min, max;
};

// Runs `update` in batches of about a millisecond; per-update time of each batch.
Timing time_per_update(const std::function<void()>& update, int repetitions) {
  using Clock = std::chrono::steady_clock;
  int batch = 1;
  for (;;) {  // calibrate
    const auto t0 = Clock::now();
    for (int i = 0; i < batch; ++i) update();
    if (Clock::now() - t0 > std::chrono::microseconds(500) || batch > (1 << 24)) break;
    batch *= 2;
  }
  std::vector<double> ns;
  for (int r = 0; r < repetitions; ++r) {
    const auto t0 = Clock::now();
    for (int i = 0; i < batch; ++i) update();
    ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / batch);
  }
  std::sort(ns.begin(), ns.end());
  return {ns[ns.size() / 2], ns.front(), ns.back()};
}

struct Scene {
  std::string name;
  Model model;
};

template <typename S>
JointState<S> cast_state(const Model& model, const JointState<double>& state) {
  JointState<S> out(model);
  out.position = state.position.cast<S>();
  out.velocity = state.velocity.cast<S>();
  out.acceleration = state.acceleration.cast<S>();
  return out;
}

// Error of one formulation in scalar S on a few random states (the largest), and its time.
template <typename S, bool kPartial>
Row formulation_row(const std::string& method, const Scene& scene, int states, int repetitions) {
  std::mt19937 rng(7);
  const Model& model = scene.model;
  Data<S> data(model);
  std::unique_ptr<PartialVelocities<S>> pv;  // O(N * depth): only when used
  if (kPartial) pv = std::make_unique<PartialVelocities<S>>(model);
  Data<Quad> reference(model);
  double error = 0;
  JointState<S> state(model);
  for (int i = 0; i < states; ++i) {
    state = cast_state<S>(model, random_state(model, rng));
    if (kPartial)
      partial_velocity_kinematics(model, state, *pv, data);
    else
      forward_kinematics(model, state, data);
    JointState<Quad> exact(model);  // the method's own inputs, exactly
    exact.position = state.position.template cast<Quad>();
    exact.velocity = state.velocity.template cast<Quad>();
    exact.acceleration = state.acceleration.template cast<Quad>();
    forward_kinematics(model, exact, reference);
    error = std::max(error, kinematics_error(data, reference).max());
  }
  const Timing t = time_per_update(
      [&] {
        if (kPartial)
          partial_velocity_kinematics(model, state, *pv, data);
        else
          forward_kinematics(model, state, data);
      },
      repetitions);
  return {method, scene.name, t.median, t.min, t.max, error, ""};
}

void formulation_rows(const Scene& scene, bool quick, std::vector<Row>& rows) {
  const int reps = quick ? 5 : 15, states = quick ? 3 : 10;
  const bool small = scene.model.body_count() <= 200;  // partial velocities are O(N * depth)
  rows.push_back(formulation_row<double, false>("recursive double", scene, states, reps));
  rows.push_back(formulation_row<float, false>("recursive float", scene, states, reps));
  rows.push_back(formulation_row<long double, false>("recursive long double", scene, states, reps));
  if (small) {
    rows.push_back(formulation_row<double, true>("partial velocity double", scene, states, reps));
    rows.push_back(formulation_row<float, true>("partial velocity float", scene, states, reps));
  }
  bool has_angles = false;
  for (const Body& b : scene.model.bodies)
    has_angles |= b.joint.type == JointType::kBall123 || b.joint.type == JointType::kFree123;
  if (!has_angles) return;
  for (SpeedKind speeds : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity}) {
    const bool quasi = speeds == SpeedKind::kAngularVelocity;
    const Scene euler{scene.name, with_euler_parameters(scene.model, speeds)};
    const std::string suffix = quasi ? " Euler w-speeds" : " Euler e'-speeds";
    rows.push_back(
        formulation_row<double, false>("recursive double" + suffix, euler, states, reps));
    if (small)
      rows.push_back(
          formulation_row<double, true>("partial velocity double" + suffix, euler, states, reps));
  }
}

std::vector<Scene> scenes(bool quick) {
  const std::string config = std::string(MBK_SOURCE_DIR) + "/config/";
  std::vector<Scene> out = {
      {"ten_body", load_model_file(config + "ten_body.yaml")},
      {"human_body", load_model_file(config + "human_body.yaml")},
      {"chain_100", make_chain(100, JointType::kBall123)},
      {"random_tree_50", make_random_tree(50, 11)},
  };
  if (!quick) out.push_back({"chain_1000", make_chain(1000, JointType::kBall123)});
  return out;
}

void write_outputs(const std::vector<Row>& rows, const std::string& dir) {
  std::ofstream csv(dir + "/work_precision.csv");
  csv << "method,scene,median_ns,min_ns,max_ns,error,note\n";
  for (const Row& r : rows)
    csv << r.method << "," << r.scene << "," << r.median_ns << "," << r.min_ns << "," << r.max_ns
        << "," << r.error << "," << r.note << "\n";
  std::ofstream md(dir + "/work_precision.md");
  md << "| method | scene | median time per update | (min - max) | error | note |\n"
     << "|---|---|---:|---|---:|---|\n";
  char line[512];
  for (const Row& r : rows) {
    std::snprintf(line, sizeof line, "| %s | %s | %.4g us | %.3g - %.3g | %.2e | %s |\n",
                  r.method.c_str(), r.scene.c_str(), r.median_ns / 1e3, r.min_ns / 1e3,
                  r.max_ns / 1e3, r.error, r.note.c_str());
    md << line;
  }
}

}  // namespace
}  // namespace mbk

int main(int argc, char** argv) {
  std::string out = ".";
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc)
      out = argv[++i];
    else if (arg == "--quick")
      quick = true;
    else {
      std::cerr << "usage: mbk_work_precision [--out DIR] [--quick]\n";
      return 2;
    }
  }
  try {
    std::vector<mbk::Row> rows;
    for (const mbk::Scene& scene : mbk::scenes(quick)) {
      std::cerr << "scene " << scene.name << "\n";
      mbk::formulation_rows(scene, quick, rows);
    }
    for (const mbk::EstimatorResult& r : mbk::estimator_study(quick))
      rows.push_back({r.method, r.stream, r.median_ns, r.min_ns, r.max_ns, r.error, r.note});
    mbk::write_outputs(rows, out);
    std::cerr << "wrote " << out << "/work_precision.csv and .md (" << rows.size() << " rows)\n";
  } catch (const std::exception& e) {
    std::cerr << "mbk_work_precision: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
