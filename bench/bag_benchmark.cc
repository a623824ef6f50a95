// mbk bag (doc/recorded_data.md): the whole offline path, and its computation alone.
//
//   bag/human/<rate>Hz/bag_out        run_bag on a 10 s bag of the demo trajectories (human body
//                                     model, positions only): read, estimate, kinematics, write
//                                     OUT.bag; counters: samples/s end to end and the seconds
//                                     spent reading, computing and writing per 1000 samples
//   bag/human/<rate>Hz/bag_and_csv_out   the same with the tidy CSV too
//   bag/human_urdf/6000/csv_out       run_bag on a bag of 6000 samples (6 s at 1 kHz) of the demo
//                                     trajectories of the 37-link human URDF to OUT.csv alone (the
//                                     default estimator, auto); real time, counter samples_per_s
//   rosbag_read/human_urdf/6000       the floor: rosbag's own read of the same bag (rosbag::View
//                                     over its messages, each deserialised by instantiate<>)
//   bag/<tree12|human_urdf>/60000/h5_out   run_bag on 60 s at 1 kHz of the demo trajectories of
//                                     a 12-link tree (mbk::make_random_revolute_tree(12, 1) with
//                                     random inertias, as a URDF) or of the human URDF to OUT.h5
//                                     alone (auto, two computing threads); real time, counters
//                                     samples_per_s and cpu_us_per_sample (every thread's and
//                                     the bag check's child's CPU); rosbag_read/<model>/60000:
//                                     its floor; bag/tree12/60000/h5_out/centered_0.4s_4: with
//                                     --estimator centered_0.4s_4 (no error bars)
//   compute/<model>/<estimated|given>/threads:T   the computation as mbk bag runs it
//                                     (OfflineBatch: estimates, state checks, forward_kinematics)
//                                     on T threads, for 5 s at 1 kHz, derivatives estimated
//                                     (centered_0.4s_4) or given; real (wall) time; counter
//                                     x_real_time = samples/s / 1000
//   kinematics_only/tree100           forward_kinematics alone on the same states, one thread
//   estimates/human/<auto|butterworth_6|butterworth_auto|old_default>  the joint derivatives
//                                     alone as mbk bag estimates them (error bars included), 10 s
//                                     at 1 kHz with 1e-4 rad of noise, for the default (auto),
//                                     butterworth:6 and butterworth:auto, and the old default
//                                     (centered_0.4s_4); counter
//                                     ns_per_sample_coordinate
//   csv_rows/human                    TidyCsvWriter alone: 1000 samples of the human model's
//                                     kinematics (one row per body and the system row) to a file;
//                                     counter rows/s
//   csv_rows/human/dev_null           the same to /dev/null: the formatting without the kernel's
//                                     copy of the 7.6 MB into the page cache
//   csv_format/human_urdf             the text alone of bag/human_urdf/6000/csv_out's CSV, error
//                                     bars' columns included, 1000 samples on one thread (no file):
//                                     the digits' bound per core; counter samples_per_s
//   large_csv/human/<fwrite_64k|block_file>/GB:<3|16>   3 or 16 GB of the tidy CSV's text
//                                     (1000 samples' rows, formatted once, written again and
//                                     again) to a file in /tmp until it is on the disk (fsync;
//                                     16 GB: about 1e6 samples, 17 GB free needed): as the writer
//                                     did before
//                                     (std::fwrite of 64 kB pieces, through the page cache) and
//                                     as it does now (io/block_file.h: direct I/O past the first
//                                     GiB where the filesystem takes it); real time, counter
//                                     MB_per_s
// Models: human = config/human_body.yaml; tree100 = mbk::make_random_tree(100, 1) (joints of
// every type, 349 coordinates); revolute100 = the same tree with every joint revolute (100).
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include "mb_kinematics/analysis/demo_trajectory.h"
#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/butterworth_estimator.h"
#include "mb_kinematics/io/block_file.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/tidy_csv.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/offline/bag_command.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace {

const std::string kHuman = std::string(MBK_SOURCE_DIR) + "/config/human_body.yaml";
const std::string kHumanUrdf = std::string(MBK_SOURCE_DIR) + "/config/human_body.urdf";

// `seconds` of the demo trajectories of `model_path` at `rate` on /joint_states (positions).
std::string demo_bag(double rate, const std::string& model_path = kHuman, double seconds = 10) {
  const std::string stem = model_path == kHumanUrdf ? "urdf" : "tree12";
  const std::string path = "/tmp/mbk_bag_benchmark_" + std::to_string(int(rate)) + "_" +
                           std::to_string(int(seconds * rate)) +
                           (model_path == kHuman ? "" : "_" + stem) + ".bag";
  const mbk::Model model = mbk::load_model_file(model_path);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  sensor_msgs::JointState js;
  js.name = model.coordinate_names;
  js.position.resize(model.nq);
  for (int i = 0; i < seconds * rate; ++i) {
    const double t = 1.0 + i / rate;
    js.header.stamp = ros::Time(t);
    for (int c = 0; c < model.nq; ++c) js.position[c] = waves[c].at(t, 0);
    bag.write("/joint_states", js.header.stamp, js);
  }
  return path;
}

void bag_path(benchmark::State& state, double rate, bool csv) {
  mbk_offline::BagOptions o;
  o.input = demo_bag(rate);
  o.model = kHuman;
  o.out_bag = "/tmp/mbk_bag_benchmark_out.bag";
  if (csv) o.out_csv = "/tmp/mbk_bag_benchmark_out.csv";
  long samples = 0;
  double read = 0, compute = 0, write = 0;
  for (auto _ : state) {
    const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
    samples += s.written;
    read += s.read_seconds, compute += s.compute_seconds, write += s.write_seconds;
  }
  state.SetItemsProcessed(samples);
  const double per_k = 1000.0 / samples;
  state.counters["read_ms_per_1k"] = 1e3 * read * per_k;
  state.counters["compute_ms_per_1k"] = 1e3 * compute * per_k;
  state.counters["write_ms_per_1k"] = 1e3 * write * per_k;
}

// mbk bag from a bag of the 37-link human URDF to a CSV alone, reading included, in real time.
void bag_to_csv(benchmark::State& state) {
  mbk_offline::BagOptions o;
  o.input = demo_bag(1000, kHumanUrdf, 6);
  o.model = kHumanUrdf;
  o.out_csv = "/tmp/mbk_bag_benchmark_urdf_out.csv";
  long samples = 0;
  double read = 0;
  for (auto _ : state) {
    const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
    samples += s.written;
    read += s.read_seconds;
  }
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["read_ms_per_1k"] = 1e6 * read / samples;
}

// The 12-link tree of bag/tree12/60000/h5_out, written as a URDF once (at its first use: not
// before main, as the model's tables are made).
const std::string& tree12_urdf() {
  static const std::string path = [] {
    const std::string p = "/tmp/mbk_bag_benchmark_tree12.urdf";
    std::FILE* f = std::fopen(p.c_str(), "w");
    const mbk::Model m = mbk::with_random_inertias(mbk::make_random_revolute_tree(12, 1), 1);
    const std::string text = mbk::write_urdf(m, "tree12");
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
    return p;
  }();
  return path;
}

// mbk bag from `seconds` of a 1 kHz bag of `model_path` to an HDF5 file alone, on two computing
// threads, reading included, in real time.
// "tree12" or "human_urdf".
std::string bench_model(const std::string& name) {
  return name == "tree12" ? tree12_urdf() : kHumanUrdf;
}

// CPU seconds of this process's threads and of its children waited for (mbk bag's check of a
// bag runs in a child process).
double process_cpu_seconds() {
  double total = 0;
  for (int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    getrusage(who, &u);
    for (const timeval& t : {u.ru_utime, u.ru_stime}) total += t.tv_sec + 1e-6 * t.tv_usec;
  }
  return total;
}

// estimator: --estimator's name, empty for the default (auto).
void bag_to_h5(benchmark::State& state, const std::string& model, double seconds,
               const std::string& estimator = "") {
  const std::string model_path = bench_model(model);
  mbk_offline::BagOptions o;
  o.input = demo_bag(1000, model_path, seconds);
  o.model = model_path;
  o.out_h5 = "/tmp/mbk_bag_benchmark_out.h5";
  o.threads = 2;
  o.estimator = estimator;
  long samples = 0;
  double read = 0, compute = 0, write = 0;
  const double cpu = process_cpu_seconds();
  for (auto _ : state) {
    const mbk_offline::BagSummary s = mbk_offline::run_bag(o);
    samples += s.written;
    read += s.read_seconds, compute += s.compute_seconds, write += s.write_seconds;
  }
  state.counters["cpu_us_per_sample"] = 1e6 * (process_cpu_seconds() - cpu) / samples;
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["read_ms_per_1k"] = 1e6 * read / samples;
  state.counters["compute_ms_per_1k"] = 1e6 * compute / samples;
  state.counters["write_ms_per_1k"] = 1e6 * write / samples;
}

// rosbag's own read of the bag of `seconds` at 1 kHz of `model_path`: every message
// deserialised, nothing else.
void rosbag_read(benchmark::State& state, const std::string& model, double seconds) {
  const std::string path = demo_bag(1000, bench_model(model), seconds);
  long samples = 0;
  const double cpu = process_cpu_seconds();
  for (auto _ : state) {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
      const sensor_msgs::JointState::ConstPtr js = m.instantiate<sensor_msgs::JointState>();
      benchmark::DoNotOptimize(js->position.back());
      ++samples;
    }
  }
  state.counters["cpu_us_per_sample"] = 1e6 * (process_cpu_seconds() - cpu) / samples;
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
}

mbk::Recording recording(const mbk::Model& model, double rate, double seconds, bool given) {
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  mbk::Recording r;
  r.nq = model.nq;
  for (int i = 0; i < rate * seconds; ++i) {
    const double t = i / rate;
    r.stamp.push_back(t);
    for (int c = 0; c < model.nq; ++c) {
      r.position.push_back(waves[c].at(t, 0));
      r.velocity.push_back(waves[c].at(t, 1));
      r.acceleration.push_back(waves[c].at(t, 2));
      r.given.push_back(given ? 7 : 1);
    }
  }
  return r;
}

// forward_kinematics on the recorded states alone (no estimates, checks or threads), to split
// the computation's time between the estimates and the kinematics.
void kinematics_only(benchmark::State& state, const mbk::Model& model) {
  const mbk::Recording rec = recording(model, 1000, 5, true);
  mbk::JointState<double> s(model);
  mbk::Data<double> d(model);
  long samples = 0;
  for (auto _ : state) {
    for (int r = 0; r < rec.rows(); ++r) {
      s.position = Eigen::Map<const Eigen::VectorXd>(rec.position.data() + r * model.nq, model.nq);
      s.velocity = Eigen::Map<const Eigen::VectorXd>(rec.velocity.data() + r * model.nq, model.nq);
      s.acceleration =
          Eigen::Map<const Eigen::VectorXd>(rec.acceleration.data() + r * model.nq, model.nq);
      mbk::forward_kinematics(model, s, d, mbk::Level::kAcceleration);
      benchmark::DoNotOptimize(d.mass_center_acceleration.back());
    }
    samples += rec.rows();
  }
  state.SetItemsProcessed(samples);
  state.counters["x_real_time"] = benchmark::Counter(samples / 1000.0, benchmark::Counter::kIsRate);
}

// The computation as mbk bag runs it (OfflineBatch: estimates, checks, kinematics) on
// state.range(0) threads, block by block, without writing; real time, since threads run at once.
void compute(benchmark::State& state, const mbk::Model& model, bool given) {
  const mbk::Recording rec = recording(model, 1000, 5, given);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_0.4s_4");
  const int threads = static_cast<int>(state.range(0));
  const int block = mbk::OfflineBatch(model, rec, e, 0, nullptr, threads).rows_per_block(4 << 20);
  std::vector<mbk::OfflineRow> rows(block, mbk::OfflineRow(model));
  long samples = 0;
  for (auto _ : state) {
    mbk::OfflineBatch batch(model, rec, e, 0, nullptr, threads);
    for (int begin = 0; begin < rec.rows(); begin += block)
      batch.compute(begin, std::min(begin + block, rec.rows()), rows);
    benchmark::DoNotOptimize(rows.back().data.mass_center_acceleration.back());
    samples += rec.rows();
  }
  state.SetItemsProcessed(samples);
  state.counters["coordinates"] = model.nq;
  state.counters["x_real_time"] = benchmark::Counter(samples / 1000.0, benchmark::Counter::kIsRate);
}

// Both derivatives of every coordinate at every sample: "auto" by estimate_auto, a fixed one by
// its weights once per sample for all coordinates (apply_weights), as OfflineStates does.
void estimates(benchmark::State& state, const mbk::Model& model, const std::string& name) {
  const mbk::Recording rec = recording(model, 1000, 10, false);
  std::vector<double> x = rec.position;
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 1e-4);
  for (double& v : x) v += noise(rng);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator(name);
  const int nq = model.nq, rows = rec.rows();
  std::vector<double> first(static_cast<size_t>(rows) * nq), second(first.size());
  long values = 0;
  for (auto _ : state) {
    const double max_gap = mbk::default_max_gap(rec.stamp);
    if (e.whole_series()) {
      mbk::AutoEstimate a;
      mbk::estimate_with_errors(e, rec.stamp, x.data(), nq, nq, max_gap, a);
      benchmark::DoNotOptimize(a.second.back());
    } else {
      const mbk::Segments segments = mbk::find_segments(rec.stamp, max_gap);
      mbk::DerivativeWeights w;
      for (int r = 0; r < rows; ++r) {
        mbk::derivative_weights(e, rec.stamp, segments, r, w);
        mbk::apply_weights(w, x.data(), nq, nq, &first[r * nq], &second[r * nq]);
      }
      benchmark::DoNotOptimize(second.back());
    }
    values += static_cast<long>(rows) * nq;
  }
  state.counters["ns_per_sample_coordinate"] =
      benchmark::Counter(static_cast<double>(values) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The tidy CSV writer alone, on computed kinematics (the demo trajectories at 1 kHz).
// Every row's kinematics, from the recording's given derivatives.
std::vector<mbk::Data<double>> kinematics_of(const mbk::Model& model, const mbk::Recording& rec) {
  std::vector<mbk::Data<double>> data(rec.rows(), mbk::Data<double>(model));
  mbk::JointState<double> s(model);
  for (int r = 0; r < rec.rows(); ++r) {
    s.position = Eigen::Map<const Eigen::VectorXd>(rec.position.data() + r * model.nq, model.nq);
    s.velocity = Eigen::Map<const Eigen::VectorXd>(rec.velocity.data() + r * model.nq, model.nq);
    s.acceleration =
        Eigen::Map<const Eigen::VectorXd>(rec.acceleration.data() + r * model.nq, model.nq);
    mbk::forward_kinematics(model, s, data[r], mbk::Level::kAcceleration);
  }
  return data;
}

void csv_rows(benchmark::State& state, const mbk::Model& model, const char* path) {
  const mbk::Recording rec = recording(model, 1000, 1, true);
  const std::vector<mbk::Data<double>> data = kinematics_of(model, rec);
  long rows = 0;
  for (auto _ : state) {
    mbk::TidyCsvWriter w(path, model);
    for (int r = 0; r < rec.rows(); ++r) w.write(rec.stamp[r], data[r]);
    w.close();
    rows += rec.rows() * (model.body_count() + 1);
  }
  state.counters["rows_per_s"] = benchmark::Counter(rows, benchmark::Counter::kIsRate);
}

// The CSV's text of bag_to_csv's samples alone (TidyCsvWriter::format with the error bars'
// columns, into a reused string) on one thread: what the digits cost per sample and core.
void csv_format(benchmark::State& state) {
  const mbk::Model model = mbk::load_model_file(kHumanUrdf);
  const mbk::Recording rec = recording(model, 1000, 1, true);
  const std::vector<mbk::Data<double>> data = kinematics_of(model, rec);
  std::vector<mbk::Vec3<double>> alpha_se(model.bodies.size()),
      acceleration_se(model.bodies.size());
  for (size_t k = 0; k < alpha_se.size(); ++k) {
    alpha_se[k] = mbk::Vec3<double>(1, 2, 3) * 1e-10 * (k + 1.0);
    acceleration_se[k] = 3 * alpha_se[k];
  }
  mbk::TidyCsvWriter w("/dev/null", model, true);
  std::string text;
  long samples = 0;
  for (auto _ : state) {
    for (int r = 0; r < rec.rows(); ++r) {
      text.clear();
      w.format(rec.stamp[r], data[r], text, &alpha_se, &acceleration_se);
    }
    benchmark::DoNotOptimize(text.data());
    samples += rec.rows();
  }
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
}

// The text of csv_rows's 1000 samples.
std::string csv_text(const mbk::Model& model) {
  const mbk::Recording rec = recording(model, 1000, 1, true);
  const std::vector<mbk::Data<double>> data = kinematics_of(model, rec);
  mbk::TidyCsvWriter w("/dev/null", model);
  std::string all;
  for (int r = 0; r < rec.rows(); ++r) w.format(rec.stamp[r], data[r], all);
  return all;
}

void large_csv(benchmark::State& state, const mbk::Model& model, bool block_file) {
  const std::string text = csv_text(model);
  const std::string path = "/tmp/mbk_bag_benchmark_large.csv";
  const long copies = static_cast<long>(state.range(0) * 1e9 / static_cast<double>(text.size()));
  constexpr std::size_t kPiece = 1 << 16;
  for (auto _ : state) {
    if (block_file) {
      mbk::BlockFile f(path);
      for (long i = 0; i < copies; ++i) f.write(text);
      f.close();
    } else {
      std::FILE* f = std::fopen(path.c_str(), "w");
      for (long i = 0; i < copies; ++i)
        for (std::size_t at = 0; at < text.size(); at += kPiece)
          std::fwrite(text.data() + at, 1, std::min(kPiece, text.size() - at), f);
      std::fclose(f);
    }
    const int fd = ::open(path.c_str(), O_WRONLY);  // what the page cache still holds, to the disk
    ::fsync(fd);
    ::close(fd);
    std::remove(path.c_str());
  }
  state.counters["MB_per_s"] = benchmark::Counter(
      1e-6 * static_cast<double>(text.size()) * copies * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

const mbk::Model& human() {
  static const mbk::Model m = mbk::load_model_file(kHuman);
  return m;
}
const mbk::Model& tree100() {
  static const mbk::Model m = mbk::make_random_tree(100, 1);
  return m;
}
const mbk::Model& revolute100() {
  static const mbk::Model m = mbk::make_random_revolute_tree(100, 1);
  return m;
}

BENCHMARK_CAPTURE(bag_path, human / 100Hz / bag_out, 100.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bag_path, human / 1000Hz / bag_out, 1000.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bag_path, human / 1000Hz / bag_and_csv_out, 1000.0, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(bag_to_csv)
    ->Name("bag/human_urdf/6000/csv_out")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(rosbag_read, human_urdf / 6000, "human_urdf", 6.0)
    ->Name("rosbag_read/human_urdf/6000")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bag_to_h5, tree12 / 60000 / h5_out, "tree12", 60.0)
    ->Name("bag/tree12/60000/h5_out")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bag_to_h5, tree12 / 60000 / h5_out / centered, "tree12", 60.0, "centered_0.4s_4")
    ->Name("bag/tree12/60000/h5_out/centered_0.4s_4")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(rosbag_read, tree12 / 60000, "tree12", 60.0)
    ->Name("rosbag_read/tree12/60000")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bag_to_h5, human_urdf / 60000 / h5_out, "human_urdf", 60.0)
    ->Name("bag/human_urdf/60000/h5_out")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(rosbag_read, human_urdf / 60000, "human_urdf", 60.0)
    ->Name("rosbag_read/human_urdf/60000")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(compute, human / estimated, human(), false)
    ->ArgName("threads")
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(compute, tree100 / estimated, tree100(), false)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(compute, tree100 / given, tree100(), true)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(compute, revolute100 / estimated, revolute100(), false)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(kinematics_only, tree100, tree100())->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(estimates, human / auto, human(), "auto") -> Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(estimates, human / butterworth_6, human(), "butterworth:6")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(estimates, human / butterworth_auto, human(), "butterworth:auto")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(estimates, human / old_default, human(), "centered_0.4s_4")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(csv_rows, human, human(), "/tmp/mbk_bag_benchmark_rows.csv")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(csv_rows, human / dev_null, human(), "/dev/null")->Unit(benchmark::kMillisecond);
BENCHMARK(csv_format)->Name("csv_format/human_urdf")->Unit(benchmark::kMillisecond);
// large_csv's sizes (GB), one iteration each (16 GB takes seconds), in real time.
void large_csv_runs(benchmark::internal::Benchmark* b) {
  b->ArgName("GB")->Arg(3)->Arg(16)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK_CAPTURE(large_csv, human / fwrite_64k, human(), false)->Apply(large_csv_runs);
BENCHMARK_CAPTURE(large_csv, human / block_file, human(), true)->Apply(large_csv_runs);

}  // namespace

BENCHMARK_MAIN();
