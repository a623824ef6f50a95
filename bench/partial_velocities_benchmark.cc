// The cost of one ~get_partial_velocities request for the tip of a deep chain,
// the core's part of it (the node adds the message), both ways in the same run:
//
//   partial_velocities/chainN/tip/whole_tree   what the service did before: the whole tree's
//       arrays (PartialVelocities, O(N x depth) columns, allocated per request as it did),
//       partial_velocity_kinematics, then independent_columns of the tip
//   partial_velocities/chainN/tip/chain        chain_partial_velocities of the tip: its chain
//       only (what the service does now)
//
// chainN: mbk::make_chain(N, revolute). The whole tree's arrays of the 10,000-link chain would
// take 7.2 GB: that row is left out. Run with --benchmark_repetitions=5 for medians
// (doc/node.md, "~get_partial_velocities").
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/chain_partial_velocity.h"
#include "mb_kinematics/core/partial_velocity.h"

namespace {

struct Scene {
  explicit Scene(int n) : model(mbk::make_chain(n, mbk::JointType::kRevolute)), state(model) {
    std::mt19937 rng(1);
    state = mbk::random_state(model, rng);
  }
  mbk::Model model;
  mbk::JointState<double> state;
};

void whole_tree(benchmark::State& bench, int n) {
  const Scene s(n);
  for (auto _ : bench) {
    mbk::PartialVelocities<double> pv(s.model);
    mbk::Data<double> data(s.model);
    mbk::partial_velocity_kinematics(s.model, s.state, pv, data);
    benchmark::DoNotOptimize(mbk::independent_columns(s.model, pv, n));
  }
}

void chain(benchmark::State& bench, int n) {
  const Scene s(n);
  for (auto _ : bench)
    benchmark::DoNotOptimize(mbk::chain_partial_velocities(s.model, s.state, {n}));
}

BENCHMARK_CAPTURE(whole_tree, chain2000, 2000)
    ->Name("partial_velocities/chain2000/tip/whole_tree")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(chain, chain2000, 2000)
    ->Name("partial_velocities/chain2000/tip/chain")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(chain, chain10000, 10000)
    ->Name("partial_velocities/chain10000/tip/chain")
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
