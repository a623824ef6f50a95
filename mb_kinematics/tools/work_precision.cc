// mbk_work_precision: error against run time for every method
// (doc/error_vs_runtime.md).
// Writes <out>/work_precision.csv and <out>/work_precision.md; scripts/work_precision.sh runs it
// and plots the CSV. Error: see mb_kinematics/analysis/kinematics_error.h; reference: the same
// recursion in quad precision (boost float128) on the method's own inputs.
//   mbk_work_precision [--out DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
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
#include "mb_kinematics/analysis/reference_kinematics.h"
#include "mb_kinematics/analysis/system_error.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/estimation/offline_estimator.h"
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
    // The reference: the method's own inputs, exactly.
    forward_kinematics(model, cast_state<Quad>(model, state), reference);
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

// The system quantities (doc/method.md 9) from the double recursion, against the same in quad
// precision (system_error.h); bodies without an inertia get a random one (with_random_inertias) so
// that the angular momentum is measured too. The time is that of system_kinematics alone.
Row system_row(const Scene& scene, int states, int repetitions) {
  std::mt19937 rng(7);
  const Model model = with_random_inertias(scene.model, 3);
  Data<double> data(model);
  Data<Quad> reference(model);
  SystemKinematics<double> system;
  SystemKinematics<Quad> system_reference;
  double error = 0;
  for (int i = 0; i < states; ++i) {
    const JointState<double> state = random_state(model, rng);
    forward_kinematics(model, state, data);
    system_kinematics(model, data, system);
    forward_kinematics(model, cast_state<Quad>(model, state), reference);
    system_kinematics(model, reference, system_reference);
    error = std::max(error, system_error(model, system, system_reference, reference));
  }
  const Timing t = time_per_update([&] { system_kinematics(model, data, system); }, repetitions);
  return {"system quantities double", scene.name, t.median, t.min, t.max, error,
          "after the recursion"};
}

void formulation_rows(const Scene& scene, bool quick, std::vector<Row>& rows) {
  const int reps = quick ? 5 : 15, states = quick ? 3 : 10;
  const bool small = scene.model.body_count() <= 200;  // partial velocities are O(N * depth)
  rows.push_back(formulation_row<double, false>("recursive double", scene, states, reps));
  rows.push_back(formulation_row<float, false>("recursive float", scene, states, reps));
  rows.push_back(formulation_row<long double, false>("recursive long double", scene, states, reps));
  rows.push_back(system_row(scene, states, reps));
  if (small) {
    rows.push_back(formulation_row<double, true>("partial velocity double", scene, states, reps));
    rows.push_back(formulation_row<float, true>("partial velocity float", scene, states, reps));
  }
  bool has_angles = false;
  for (const Body& b : scene.model.bodies)
    has_angles |= takes_euler_order(b.joint.type);
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

// Values of rows in first-seen order, e.g. the methods or the scenes.
std::vector<std::string> distinct(const std::vector<Row>& rows, std::string Row::*field) {
  std::vector<std::string> out;
  for (const Row& r : rows)
    if (std::find(out.begin(), out.end(), r.*field) == out.end()) out.push_back(r.*field);
  return out;
}

const Row* find_row(const std::vector<Row>& rows, const std::string& method,
                    const std::string& scene) {
  for (const Row& r : rows)
    if (r.method == method && r.scene == scene) return &r;
  return nullptr;
}

// Formulations: a row per method, a column per scene, "error (median time)".
void write_formulation_table(std::ostream& md, const std::vector<Row>& rows) {
  const auto scenes = distinct(rows, &Row::scene);
  md << "| method |";
  for (const auto& s : scenes) md << " " << s << " |";
  md << "\n|---|";
  for (size_t i = 0; i < scenes.size(); ++i) md << "---:|";
  md << "\n";
  char cell[64];
  for (const auto& method : distinct(rows, &Row::method)) {
    md << "| " << method << " |";
    for (const auto& scene : scenes) {
      const Row* r = find_row(rows, method, scene);
      if (r) std::snprintf(cell, sizeof cell, " %.1e (%.3g us) |", r->error, r->median_ns / 1e3);
      md << (r ? cell : " - |");
    }
    md << "\n";
  }
}

// Estimators: a row per estimator, a column per stream, the acceleration error.
void write_estimator_table(std::ostream& md, const std::vector<Row>& rows) {
  const auto streams = distinct(rows, &Row::scene);
  md << "| estimator | offline | latency | ns per sample |";
  for (const auto& s : streams) md << " " << s << " |";
  md << "\n|---|---|---:|---:|";
  for (size_t i = 0; i < streams.size(); ++i) md << "---:|";
  md << "\n";
  char cell[64];
  for (const auto& method : distinct(rows, &Row::method)) {
    const Row* first = find_row(rows, method, streams.front());
    const std::string latency = first->note.substr(first->note.find("latency ") + 8);
    std::snprintf(cell, sizeof cell, " %.3g |", first->median_ns);
    const bool offline = first->note.find("offline") != std::string::npos;
    md << "| " << method << " | " << (offline ? "yes (mbk bag)" : "no (node)") << " | "
       << latency.substr(0, latency.find(' ')) << " |" << cell;
    for (const auto& stream : streams) {
      const Row* r = find_row(rows, method, stream);
      std::snprintf(cell, sizeof cell, " %.1e |", r ? r->error : NAN);
      md << cell;
    }
    md << "\n";
  }
}

// mbk bag's default (auto) against the best fixed offline estimator in hindsight and the old
// default (centered_0.4s_4), per stream: the acceleration error, ends included.
void write_default_table(std::ostream& md, const std::vector<Row>& rows) {
  md << "| stream | default auto | best fixed (in hindsight) | old default centered_0.4s_4 |\n"
        "|---|---:|---:|---:|\n";
  char line[192];
  for (const auto& stream : distinct(rows, &Row::scene)) {
    const Row *automatic = find_row(rows, "auto", stream),
              *old = find_row(rows, "centered_0.4s_4", stream), *best = nullptr;
    if (!automatic || !old) continue;
    for (const Row& r : rows)
      if (r.scene == stream && r.method != "auto" && r.note.find("offline") != std::string::npos &&
          (!best || r.error < best->error))
        best = &r;
    std::snprintf(line, sizeof line, "| %s | %.1e (%.2fx) | %.1e (%s) | %.1e |\n", stream.c_str(),
                  automatic->error, automatic->error / best->error, best->error,
                  best->method.c_str(), old->error);
    md << line;
  }
}

void write_outputs(const std::vector<Row>& formulations, const std::vector<Row>& estimators,
                   const std::string& dir) {
  std::ofstream csv(dir + "/work_precision.csv");
  csv << "method,scene,median_ns,min_ns,max_ns,error,note\n";
  for (const auto* rows : {&formulations, &estimators})
    for (const Row& r : *rows)
      csv << r.method << "," << r.scene << "," << r.median_ns << "," << r.min_ns << "," << r.max_ns
          << "," << r.error << "," << r.note << "\n";
  std::ofstream md(dir + "/work_precision.md");
  md << "Kinematics: largest relative error over bodies and quantities against the quad-precision "
        "reference, and (median run time per update):\n\n";
  write_formulation_table(md, formulations);
  md << "\nJoint accelerations estimated from positions only: largest error relative to the "
        "signal's largest acceleration, per stream (rate, timestamp jitter, position noise in "
        "rad); latency in samples; run time per sample and coordinate. The node's estimators "
        "(offline: no) are measured after a 1 s warm-up; mbk bag's zero-phase ones (offline: yes) "
        "over every sample, the recording's ends included:\n\n";
  write_estimator_table(md, estimators);
  md << "\nmbk bag's default (`auto`) against the best fixed offline estimator chosen in hindsight "
        "for each stream (the factor in brackets: auto / best) and the old default:\n\n";
  write_default_table(md, estimators);
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
    std::vector<mbk::Row> formulations, estimators;
    for (const mbk::Scene& scene : mbk::scenes(quick)) {
      std::cerr << "scene " << scene.name << "\n";
      mbk::formulation_rows(scene, quick, formulations);
    }
    std::cerr << "estimators\n";
    const mbk::Model human =
        mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/config/human_body.yaml");
    for (const mbk::EstimatorResult& r : mbk::estimator_study(mbk::demo_waves(human), quick))
      estimators.push_back({r.method, r.stream, r.median_ns, r.min_ns, r.max_ns, r.error, r.note});
    // mbk bag's estimators on a human-like recording (0.2 to 5 Hz), 20 % jitter.
    for (const std::string& name : mbk::offline_estimator_names())
      for (double rate : {100.0, 1000.0})
        for (double noise : {0.0, 1e-4, 1e-3, 1e-2}) {
          const mbk::EstimatorResult r = mbk::run_offline_estimator(
              name, mbk::human_like_waves(human), rate, 0.2, noise, quick ? 4.0 : 10.0, 1);
          estimators.push_back({r.method, "human-like " + r.stream, r.median_ns, r.min_ns, r.max_ns,
                                r.error, r.note});
        }
    mbk::write_outputs(formulations, estimators, out);
    std::cerr << "wrote " << out << "/work_precision.csv and .md\n";
  } catch (const std::exception& e) {
    std::cerr << "mbk_work_precision: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
