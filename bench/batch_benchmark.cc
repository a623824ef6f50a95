// mbk::batch_kinematics (offline/batch_kinematics.h), the C++ under the Python module's
// Model.kinematics, into preallocated arrays (doc/speed.md#python, bench/python_batch.py):
//
//   batch/<model>/<outputs>/threads:T   N = 1e5 random states (uniform +-0.5 in every coordinate,
//                                       speed and acceleration) of <model> into arrays allocated
//                                       and touched once before timing; <outputs> = full (the 13
//                                       outputs the Python call gives by default with
//                                       accelerations), all (every output but the partial
//                                       velocities: full and the opt-in segment frames and joint
//                                       motion, 20 outputs) or pose (rotation and origin); real
//                                       time; counters ns_per_sample, ns_per_body_sample, GB_per_s
//                                       (the bytes of the outputs written per second)
//   copy/<model>/<outputs>/threads:T    memcpy of the same bytes between two such arrays (the
//                                       physical limit of writing the outputs), split the same way
//   compute/<model>/<outputs>/threads:T the same states' batch on T threads with every sample
//                                       written into one sample's arrays (in L1): the computation
//                                       less the outputs' memory traffic and the state check
//   check/<model>/<outputs>/threads:T   the state check alone (the batch's first pass)
//   write/<model>/<outputs>/threads:T   the writes alone: one sample's outputs (in L1) stored
//                                       into every sample's rows of arrays touched before, with
//                                       ordinary stores (each line read for ownership first)
//   stream/<model>/<outputs>/threads:T  the same with streaming (non-temporal) stores: each line
//                                       written once, never read (stream_copy, as the batch's)
//   batch4/<model>/<outputs>/threads:T  batch/ with four samples at once at most (most_lanes 4),
//                                       as on a CPU with AVX2 and no AVX-512F
//   kinematics/, lanes4/, lanes8/       the recursion and the system's sums alone, nothing
//                                       written: one sample at a time, four and eight at once
//
// Models: human = config/human_body.urdf (37 bodies), panda = test/robots/panda.urdf (7-joint
// arm, hand and fingers: 12 bodies). Arguments: --benchmark_format=json for bench/python_batch.py.
#include <benchmark/benchmark.h>
#include <sys/mman.h>

#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/kinematics_lanes.h"
#include "mb_kinematics/core/split_runs.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/batch_kinematics.h"
#include "mb_kinematics/offline/stream_copy.h"

namespace {

constexpr std::size_t kSamples = 100000;

// Memory of 1 MiB and more with transparent huge pages asked for (madvise) before its first touch,
// as the Python module's fresh arrays (offline/retained_blocks.h) and numpy's np.empty above 4
// MiB; smaller from malloc (one sample's arrays: each on a page of its own would share the
// caches' sets with the others).
template <typename T>
struct HugePages {
  using value_type = T;
  HugePages() = default;
  template <typename U>
  explicit HugePages(const HugePages<U>&) {}
  static bool large(std::size_t n) { return n * sizeof(T) >= (std::size_t{1} << 20); }
  T* allocate(std::size_t n) {
    void* p = large(n) ? mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE,
                              MAP_PRIVATE | MAP_ANONYMOUS, -1, 0)
                       : std::malloc(n * sizeof(T));
    if (p == MAP_FAILED || p == nullptr) throw std::bad_alloc();
    if (large(n)) madvise(p, n * sizeof(T), MADV_HUGEPAGE);
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (large(n))
      munmap(p, n * sizeof(T));
    else
      std::free(p);
  }
  bool operator==(const HugePages&) const { return true; }
  bool operator!=(const HugePages&) const { return false; }
};
template <typename T>
using Array = std::vector<T, HugePages<T>>;

const mbk::Model& model_of(const std::string& name) {
  static const mbk::Model human =
      mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/config/human_body.urdf");
  static const mbk::Model panda =
      mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/test/robots/panda.urdf");
  return name == "human" ? human : panda;
}

enum class Outputs { kPose, kFull, kAll };
const char* const kOutputNames[] = {"pose", "full", "all"};

// Whether a batch of `outputs` writes `field`.
bool writes(Outputs outputs, mbk::BatchField field) {
  switch (outputs) {
    case Outputs::kPose:
      return field == mbk::BatchField::kRotation || field == mbk::BatchField::kOrigin;
    case Outputs::kFull:
      return field <= mbk::BatchField::kAngularMomentum;
    case Outputs::kAll:
      return mbk::batch_field_traits(field).width != 0;  // all but the partial velocities
  }
  return false;
}

// The inputs (unless `states` is false) and every output array of a run (`samples` rows: one
// for compute's), allocated and touched once.
struct Batch {
  Batch(const mbk::Model& model, Outputs outputs, std::size_t samples = kSamples,
        bool states = true) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (Array<double>* x : {&q, &v, &a}) {
      x->resize(states ? kSamples * (x == &q ? model.nq : model.nv) : 0);
      for (double& value : *x) value = u(rng);
    }
    in.samples = kSamples;
    in.position = q.data();
    in.velocity = v.data();
    in.acceleration = a.data();
    for (int k = 1; k <= model.body_count(); ++k) out.bodies.push_back(k);
    arrays.reserve(mbk::kBatchFieldCount);
    for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
      const auto field = static_cast<mbk::BatchField>(f);
      if (!writes(outputs, field)) continue;
      arrays.emplace_back(samples * mbk::batch_field_size(model, field, out.bodies.size()), 0.0);
      out[field] = arrays.back().data();
      bytes += arrays.back().size() * sizeof(double);
      bytes_per_sample += mbk::batch_field_size(model, field, out.bodies.size()) * sizeof(double);
    }
  }
  Array<double> q, v, a;
  mbk::BatchInput in;
  std::vector<Array<double>> arrays;
  mbk::BatchOutput<double> out;
  std::size_t bytes = 0, bytes_per_sample = 0;
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

template <int kMostLanes>
void batch(benchmark::State& state, const std::string& name, Outputs outputs) {
  const mbk::Model& model = model_of(name);
  Batch b(model, outputs);
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) mbk::batch_kinematics(model, b.in, b.out, threads, kMostLanes);
  set_counters(state, model, b.bytes);
}

// Row s of the batch's states into `joints` (sized for the model), mimic coordinates from their
// sources, as the batch's load_sample: a memcpy of each row.
void load(const mbk::Model& model, const Batch& b, std::size_t s, mbk::JointState<double>& joints) {
  const auto row = [s](const Array<double>& rows, int width, Eigen::VectorXd& to) {
    std::memcpy(to.data(), rows.data() + s * width,
                static_cast<std::size_t>(width) * sizeof(double));
  };
  row(b.q, model.nq, joints.position);
  row(b.v, model.nv, joints.velocity);
  row(b.a, model.nv, joints.acceleration);
  mbk::apply_mimics(model, joints);
}

// What batch_kinematics computes and writes for each sample one at a time (its compute_sample: the
// path of partial velocities, float32 and CPUs without AVX2; `lanes4/` and `lanes8/` for the
// samples at once of the others), every sample into one sample's arrays per thread, at the level
// the outputs need: no output leaves the caches.
void compute(benchmark::State& state, const std::string& name, Outputs outputs) {
  const mbk::Model& model = model_of(name);
  const Batch b(model, outputs, 0);  // for its states
  const int threads = static_cast<int>(state.range(0));
  const mbk::Level level = mbk::batch_level(Batch(model, outputs, 1, false).out);
  for (auto _ : state)
    mbk::split_runs(kSamples, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
      Batch one(model, outputs, 1, false);
      mbk::JointState<double> joints(model);
      mbk::Data<double> data(model);
      mbk::SystemKinematics<double> system;
      for (std::size_t s = begin; s < end; ++s) {
        load(model, b, s, joints);
        mbk::forward_kinematics(model, joints, data, level);
        mbk::write_batch_fields(model, data, 0, level, one.out, system);
        benchmark::DoNotOptimize(one.arrays.front().data());
      }
    });
  set_counters(state, model, 0);
}

// Lane l of x: x itself for a double.
template <typename S>
double& lane(S& x, std::size_t l) {
  if constexpr (std::is_same_v<S, double>)
    return x;
  else
    return x.v[l];
}

// Row s of the batch's states into lane l of `joints`, number by number.
template <typename S>
void load_lane(const mbk::Model& model, const Batch& b, std::size_t s, std::size_t l,
               mbk::JointState<S>& joints) {
  for (int i = 0; i < model.nq; ++i) lane(joints.position[i], l) = b.q[s * model.nq + i];
  for (int i = 0; i < model.nv; ++i) {
    lane(joints.velocity[i], l) = b.v[s * model.nv + i];
    lane(joints.acceleration[i], l) = b.a[s * model.nv + i];
  }
}

// The recursion and the system's sums alone, at `level`, nothing written, for groups [begin, end)
// of sizeof(S) / sizeof(double) samples: one sample at a time in double, four or eight at once in
// the lanes of a Double4 or Double8 (core/kinematics_lanes.h; the batch's path in double without
// partial velocities), each lane loaded number by number.
template <typename S>
void kinematics_run(const mbk::Model& model, const Batch& b, mbk::Level level, std::size_t begin,
                    std::size_t end) {
  constexpr std::size_t kLanes = sizeof(S) / sizeof(double);
  mbk::JointState<S> joints(model);
  mbk::Data<S> data(model);
  mbk::SystemKinematics<S> system;
  for (std::size_t g = begin; g < end; ++g) {
    for (std::size_t l = 0; l < kLanes; ++l) load_lane(model, b, g * kLanes + l, l, joints);
    mbk::apply_mimics(model, joints);
    mbk::forward_kinematics(model, joints, data, level);
    mbk::system_kinematics(model, data, system, level);
    benchmark::DoNotOptimize(&system);
  }
}

// kinematics_run on every sample: `kinematics/` (double), `lanes4/` (Double4), `lanes8/` (Double8).
template <typename S>
void kinematics(benchmark::State& state, const std::string& name, Outputs outputs) {
  constexpr std::size_t kLanes = sizeof(S) / sizeof(double);
  const mbk::Model& model = model_of(name);
  if (mbk::samples_at_once(model) < static_cast<int>(kLanes))
    return state.SkipWithError("not this many lanes here");
  const Batch b(model, outputs, 0);  // for its states
  const int threads = static_cast<int>(state.range(0));
  const mbk::Level level = mbk::batch_level(Batch(model, outputs, 1, false).out);
  for (auto _ : state)
    mbk::split_runs(kSamples / kLanes, threads,
                    [&](std::size_t, std::size_t begin, std::size_t end) {
                      kinematics_run<S>(model, b, level, begin, end);
                    });
  set_counters(state, model, 0);
}

// batch_kinematics' first pass: every sample's state checked (check_state) before any is written.
void check(benchmark::State& state, const std::string& name, Outputs outputs) {
  const mbk::Model& model = model_of(name);
  const Batch b(model, outputs, 0);
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state)
    mbk::split_runs(kSamples, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
      mbk::JointState<double> joints(model);
      for (std::size_t s = begin; s < end; ++s) {
        load(model, b, s, joints);
        if (!mbk::check_state(model, joints).empty()) std::abort();  // the states are all valid
      }
    });
  set_counters(state, model, 0);
}

// The same bytes copied between two arrays of that size, on `threads` threads.
void copy(benchmark::State& state, const std::string& name, Outputs outputs) {
  const mbk::Model& model = model_of(name);
  const std::size_t bytes = Batch(model, outputs, 0, false).bytes_per_sample * kSamples;
  Array<char> from(bytes, 1), to(bytes, 0);
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

// The outputs' writes without the computation: one sample's arrays (in L1) into every sample's
// rows, with ordinary stores (memcpy of a few KB) or streaming ones.
void write_rows(benchmark::State& state, const std::string& name, Outputs outputs, bool streaming) {
  const mbk::Model& model = model_of(name);
  Batch b(model, outputs, kSamples, false);
  const Batch one(model, outputs, 1, false);
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    mbk::split_runs(kSamples, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s)
        for (std::size_t i = 0; i < b.arrays.size(); ++i) {
          const std::size_t n = one.arrays[i].size();
          if (streaming)
            mbk::stream_copy(b.arrays[i].data() + s * n, one.arrays[i].data(), n * sizeof(double));
          else
            std::memcpy(b.arrays[i].data() + s * n, one.arrays[i].data(), n * sizeof(double));
        }
      mbk::stream_fence();
    });
    benchmark::DoNotOptimize(b.arrays.front().data());
  }
  set_counters(state, model, b.bytes);
}

void write(benchmark::State& state, const std::string& name, Outputs outputs) {
  write_rows(state, name, outputs, false);
}

void stream(benchmark::State& state, const std::string& name, Outputs outputs) {
  write_rows(state, name, outputs, true);
}

using Run = void (*)(benchmark::State&, const std::string&, Outputs);

void add(const char* row, Run run, const char* name, Outputs outputs) {
  benchmark::RegisterBenchmark(
      (std::string(row) + "/" + name + "/" + kOutputNames[static_cast<int>(outputs)]).c_str(),
      [run, name, outputs](benchmark::State& s) { run(s, name, outputs); })
      ->ArgName("threads")
      ->Arg(1)
      ->Arg(2)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
}

void register_all() {
  for (const char* name : {"human", "panda"}) {
    for (const Outputs outputs : {Outputs::kFull, Outputs::kPose, Outputs::kAll})
      add("batch", batch<8>, name, outputs);
    for (const Outputs outputs : {Outputs::kFull, Outputs::kAll})
      add("batch4", batch<4>, name, outputs);
    for (const Outputs outputs : {Outputs::kFull, Outputs::kAll}) {
      add("compute", compute, name, outputs);
      add("kinematics", kinematics<double>, name, outputs);
      add("lanes4", kinematics<mbk::Double4>, name, outputs);
      add("lanes8", kinematics<mbk::Double8>, name, outputs);
      add("check", check, name, outputs);
      add("copy", copy, name, outputs);
      add("write", write, name, outputs);
      add("stream", stream, name, outputs);
    }
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
