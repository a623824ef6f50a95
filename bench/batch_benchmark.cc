// mbk::batch_kinematics (offline/batch_kinematics.h), the C++ under the Python module's
// Model.kinematics, into preallocated arrays (doc/speed.md#python, bench/python_batch.py):
//
//   batch/<model>/<outputs>/threads:T   N = 1e5 random states (uniform +-0.5 in every coordinate,
//                                       speed and acceleration) of <model>, <outputs> = full
//                                       (the 13 outputs the Python call gives by default with
//                                       accelerations) or pose (rotation and origin), into arrays
//                                       allocated and touched once before timing; real time;
//                                       counters ns_per_sample, ns_per_body_sample, GB_per_s
//                                       (the bytes of the outputs written per second)
//   copy/<model>/full/threads:T         memcpy of the same bytes between two such arrays (the
//                                       physical limit of writing the outputs), split the same way
//   compute/<model>/full                the same states' recursion and system kinematics on one
//                                       thread into one Data, no output written: the batch less
//                                       its state check, its copy out of Data and the outputs'
//                                       memory traffic
//
// Models: human = config/human_body.urdf (37 bodies), panda = test/robots/panda.urdf (7-joint
// arm, hand and fingers: 12 bodies). Arguments: --benchmark_format=json for bench/python_batch.py.
#include <benchmark/benchmark.h>

#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/batch_kinematics.h"

namespace {

constexpr std::size_t kSamples = 100000;

const mbk::Model& model_of(const std::string& name) {
  static const mbk::Model human =
      mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/config/human_body.urdf");
  static const mbk::Model panda =
      mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/test/robots/panda.urdf");
  return name == "human" ? human : panda;
}

// The inputs and every output array of a run, allocated and touched once.
struct Batch {
  Batch(const mbk::Model& model, bool full) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (std::vector<double>* x : {&q, &v, &a}) {
      x->resize(kSamples * (x == &q ? model.nq : model.nv));
      for (double& value : *x) value = u(rng);
    }
    in.samples = kSamples;
    in.position = q.data();
    in.velocity = v.data();
    in.acceleration = a.data();
    for (int k = 1; k <= model.body_count(); ++k) out.bodies.push_back(k);
    const int last = full ? static_cast<int>(mbk::BatchField::kAngularMomentum)
                          : static_cast<int>(mbk::BatchField::kOrigin);
    for (int f = 0; f <= last; ++f) {
      const auto field = static_cast<mbk::BatchField>(f);
      arrays.emplace_back(kSamples * mbk::batch_field_size(model, field, out.bodies.size()), 0.0);
      out[field] = arrays.back().data();
      bytes += arrays.back().size() * sizeof(double);
    }
  }
  std::vector<double> q, v, a;
  mbk::BatchInput in;
  std::vector<std::vector<double>> arrays;
  mbk::BatchOutput<double> out;
  std::size_t bytes = 0;
};

void set_counters(benchmark::State& state, const mbk::Model& model, std::size_t bytes) {
  const double runs = static_cast<double>(state.iterations());
  state.counters["ns_per_sample"] = benchmark::Counter(
      runs * kSamples * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ns_per_body_sample"] =
      benchmark::Counter(runs * kSamples * model.body_count() * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["GB_per_s"] = benchmark::Counter(runs * bytes * 1e-9, benchmark::Counter::kIsRate);
}

void batch(benchmark::State& state, const std::string& name, bool full) {
  const mbk::Model& model = model_of(name);
  Batch b(model, full);
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) mbk::batch_kinematics(model, b.in, b.out, threads);
  set_counters(state, model, b.bytes);
}

// What batch_kinematics computes for the full outputs, without writing them (as its
// compute_sample with every output in Data and SystemKinematics only).
void compute(benchmark::State& state, const std::string& name) {
  const mbk::Model& model = model_of(name);
  const Batch b(model, false);  // for its states
  mbk::JointState<double> joints(model);
  mbk::Data<double> data(model);
  mbk::SystemKinematics<double> system;
  for (auto _ : state)
    for (std::size_t s = 0; s < kSamples; ++s) {
      joints.position = Eigen::Map<const Eigen::VectorXd>(b.q.data() + s * model.nq, model.nq);
      joints.velocity = Eigen::Map<const Eigen::VectorXd>(b.v.data() + s * model.nv, model.nv);
      joints.acceleration = Eigen::Map<const Eigen::VectorXd>(b.a.data() + s * model.nv, model.nv);
      mbk::apply_mimics(model, joints);
      mbk::forward_kinematics(model, joints, data, mbk::Level::kAcceleration);
      mbk::system_kinematics(model, data, system, mbk::Level::kAcceleration);
      benchmark::DoNotOptimize(system);
    }
  set_counters(state, model, 0);
}

// The same bytes copied between two arrays of that size, on `threads` threads.
void copy(benchmark::State& state, const std::string& name) {
  const mbk::Model& model = model_of(name);
  const std::size_t bytes = Batch(model, true).bytes;
  std::vector<char> from(bytes, 1), to(bytes, 0);
  const std::size_t threads = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        const std::size_t begin = bytes * t / threads, end = bytes * (t + 1) / threads;
        std::memcpy(to.data() + begin, from.data() + begin, end - begin);
      });
    for (std::thread& thread : pool) thread.join();
    benchmark::DoNotOptimize(to.data());
  }
  set_counters(state, model, bytes);
}

void register_all() {
  for (const char* name : {"human", "panda"}) {
    for (const bool full : {true, false})
      benchmark::RegisterBenchmark(
          ("batch/" + std::string(name) + (full ? "/full" : "/pose")).c_str(),
          [name, full](benchmark::State& s) { batch(s, name, full); })
          ->ArgName("threads")
          ->Arg(1)
          ->Arg(2)
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("compute/" + std::string(name) + "/full").c_str(),
                                 [name](benchmark::State& s) { compute(s, name); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("copy/" + std::string(name) + "/full").c_str(),
                                 [name](benchmark::State& s) { copy(s, name); })
        ->ArgName("threads")
        ->Arg(1)
        ->Arg(2)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
