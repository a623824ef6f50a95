#include "mb_kinematics/offline/bag_command.h"

#include <ros/time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mb_kinematics/core/base_joint.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/io/angle_orders.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/tidy_csv.h"
#include "mb_kinematics/offline/bag_input.h"
#include "mb_kinematics/offline/bag_output.h"
#include "mb_kinematics/offline/base_track.h"
#include "mb_kinematics/offline/bvh_recording.h"
#include "mb_kinematics/offline/error_bar_files.h"
#include "mb_kinematics/offline/h5_output.h"
#include "mb_kinematics/offline/kept_rows.h"
#include "mb_kinematics/offline/mot_output.h"
#include "mb_kinematics/offline/offline_batch.h"
#include "mb_kinematics/offline/offline_stream.h"
#include "mb_kinematics/offline/output_file.h"
#include "mb_kinematics/offline/progress.h"
#include "mb_kinematics/offline/trajectory_csv.h"

namespace mbk_offline {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool ends_with(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

// The --model file, read once; the node's model rules: coordinate-derivative speeds (JointState
// velocities are q').
mbk::ModelFile load(const std::string& path, const mbk::BvhModelOptions& bvh) {
  mbk::ModelFile file = mbk::read_model_file(path, bvh);
  mbk::Model& model = file.model;
  for (const std::string& warning : model.warnings)
    std::cerr << "mbk: warning: " << mbk::printable(warning) << "\n";
  if (model.speeds != mbk::SpeedKind::kCoordinateDerivatives) {
    model.speeds = mbk::SpeedKind::kCoordinateDerivatives;
    mbk::finalize_model(model);
  }
  return file;
}

// True if paths a and b name one file: the same device and inode (symlinks and hard links
// followed) when both exist, else the same path once the existing part is resolved. Two
// outputs that are both devices or pipes (/dev/null twice) are not refused.
bool same_file(const std::string& a, const std::string& b, bool both_outputs) {
  namespace fs = std::filesystem;
  std::error_code ea, eb;
  const fs::file_status sa = fs::status(a, ea), sb = fs::status(b, eb);
  if (fs::exists(sa) && fs::exists(sb)) {
    if (both_outputs && !fs::is_regular_file(sa) && !fs::is_regular_file(sb)) return false;
    return fs::equivalent(a, b, ea);
  }
  return fs::weakly_canonical(a, ea) == fs::weakly_canonical(b, eb);
}

// What a run writes: the outputs, the caller's other files (`others`), and with "auto"
// (`side_files`) the CSV's side files OUT.errors.csv and OUT.sample_errors.csv.
std::vector<NamedFile> written_files(const BagOutputs& o, const std::vector<NamedFile>& others,
                                     bool side_files) {
  std::vector<NamedFile> files = output_files(o);
  files.insert(files.end(), others.begin(), others.end());
  if (side_files && has_side_files(o.out_csv))
    for (const char* suffix : {".errors.csv", ".sample_errors.csv"})
      files.push_back({"--csv's side file", errors_path(o.out_csv, suffix)});
  return files;
}

// Refuses, before anything is read or written, an output that is the same file as an input or
// as another output.
void refuse_same_files(const std::vector<NamedFile>& inputs,
                       const std::vector<NamedFile>& outputs) {
  for (const NamedFile& out : outputs)
    for (const NamedFile& in : inputs)
      if (same_file(out.path, in.path, false))
        throw std::invalid_argument(out.name + " " + out.path + " is the same file as " + in.name +
                                    " " + in.path + ": refused, nothing written");
  for (size_t i = 0; i < outputs.size(); ++i)
    for (size_t j = i + 1; j < outputs.size(); ++j)
      if (same_file(outputs[i].path, outputs[j].path, true))
        throw std::invalid_argument(outputs[i].name + " " + outputs[i].path + " and " +
                                    outputs[j].name + " " + outputs[j].path +
                                    " are the same file: refused, nothing written");
}

// OUT.bag, OUT.csv, OUT.h5 and/or OUT.mot, each under a temporary name until all are whole
// (output_file.h): the writers are destroyed before the files, which remove what was not
// committed.
struct Outputs {
  std::string input;  // IN, for the stamp error
  std::unique_ptr<OutputFile> bag_file, csv_file, h5_file, mot_file;
  std::unique_ptr<BagOutput> bag;
  std::unique_ptr<mbk::TidyCsvWriter> csv;
  std::unique_ptr<H5Output> h5;
  std::unique_ptr<MotOutput> mot;
  bool floating = false, formatted = false;
  const mbk::Model* base_model = nullptr;        // with a base: the node's layout
  std::unique_ptr<mbk::Data<double>> base_data;  // of base_model
  double origin = 0;                             // the stamps' (Recording::origin)

  void set_time_origin(double seconds) {
    origin = seconds;
    if (bag) bag->set_time_origin(seconds);
    if (csv) csv->set_time_origin(seconds);
    if (h5) h5->set_time_origin(seconds);
    if (mot) mot->set_time_origin(seconds);
  }

  void write(const mbk::OfflineRow& row) {
    const mbk::Data<double>* data = &row.data;
    if (floating) mbk::with_base_body(*base_model, row.data, *base_data), data = base_data.get();
    if (bag) {
      check_bag_stamp(origin + row.stamp);
      bag->write(row.stamp, row.state, *data, floating ? &row.base : nullptr);
    }
    const bool errors = !row.alpha_se.empty();
    if (csv && formatted)
      csv->write_text(row.text);
    else if (csv)
      csv->write(row.stamp, *data, errors ? &row.alpha_se : nullptr,
                 errors ? &row.acceleration_se : nullptr);
    if (h5) h5->write(row, *data);
    if (mot) mot->write(row, *data, csv && csv->sequential() ? &csv->angles() : nullptr);
  }
  // A bag holds stamps from ros::TIME_MIN (1 ns; 0 means "no stamp") to ros::TIME_MAX only.
  void check_bag_stamp(double t) const {
    if (t >= 0 && t <= ros::TIME_MAX.toSec() && ros::Time(t) >= ros::TIME_MIN) return;
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", t);
    throw std::invalid_argument(
        input + ": time " + text +
        " s cannot be a bag's stamp (--out holds 1 ns, ros::TIME_MIN, to ros::TIME_MAX): give "
        "--start-time S to add S seconds to every time (e.g. --start-time 1); nothing written");
  }
  // The CSV's text formatted by the computing threads, beside the writing (without a base:
  // with one, the rows are carried into the base's layout here first; with --angles, each row's
  // angles continue the row before: formatted here, in order).
  mbk::OfflineBatch::Formatter formatter() {
    if (!csv || floating || csv->sequential()) return nullptr;
    formatted = true;
    return [csv = csv.get()](mbk::OfflineRow& row) {
      row.text.clear();
      const bool errors = !row.alpha_se.empty();
      csv->format(row.stamp, row.data, row.text, errors ? &row.alpha_se : nullptr,
                  errors ? &row.acceleration_se : nullptr);
    };
  }
  void close() {
    if (bag) bag->close();
    if (csv) csv->close();
    if (h5) h5->close();
    if (mot) mot->close();
    if (bag_file) bag_file->commit();
    if (csv_file) csv_file->commit();
    if (h5_file) h5_file->commit();
    if (mot_file) mot_file->commit();
  }
};

// A computed row written, or its drop counted (in order).
void take(const mbk::OfflineRow& row, Outputs& out, mbk::DropLog& log, long& written) {
  if (row.drop_reason.empty())
    out.write(row), ++written;
  else
    log.drop(row.drop_reason, row.drop_detail);
}

// Every row, computed by the batch's workers a block at a time while this thread writes the
// block before (two blocks of results), written in order; drops are counted in order.
void compute_and_write(mbk::OfflineBatch& batch, const mbk::Model& model, int rows, Outputs& out,
                       bool progress, BagSummary& s) {
  mbk::Progress bar("computing", progress);
  const mbk::RowSeconds t = mbk::compute_rows(
      batch, model, 0, rows, [&](const mbk::OfflineRow& row) { take(row, out, s.log, s.written); },
      [&](int done) { bar.update(done, rows); });
  s.compute_seconds += t.compute, s.write_seconds += t.use;
  bar.finish();
  const auto t_close = Clock::now();
  out.close();
  s.write_seconds += since(t_close);
}

// How a run reads its input (read_input) for the model of `file`.
struct InputReading {
  const BagInput& in;
  const mbk::ModelFile& file;
  double bvh_scale;  // a BVH input's frames at the model's scale
  bool is_model;     // IN is the model file (a BVH input's own skeleton): its motion is in `file`
  bool progress;
};

// Every sample of the input into `builder` (a trajectory CSV, a BVH file or a bag);
// `checked`: the bag was read safely before (read_bag). A BVH input that is the model file (the
// default) is not read again.
void read_input(const InputReading& r, mbk::RecordingBuilder& builder, BaseOdometry& base,
                BagSummary& s, bool checked) {
  const std::string& input = r.in.input;
  mbk::Progress bar("reading  ", r.progress);
  builder.offset_times(r.in.start_time);
  if (r.is_model) return mbk::add_bvh_frames(*r.file.bvh, r.file.model, r.bvh_scale, builder);
  if (mbk::is_bvh_file(input))
    return mbk::add_bvh_frames(mbk::read_bvh(input), r.file.model, r.bvh_scale, builder);
  if (ends_with(input, ".csv")) return mbk::read_trajectory_csv(input, builder);
  Unreadable unreadable;
  read_bag(
      input, r.in, builder, base, unreadable,
      [&](long done, long total) { bar.update(done, total); }, checked);
  s.unreadable = unreadable.count;
  s.unreadable_example = mbk::printable(unreadable.first);  // librosbag's text: the bag's bytes
}

// The outputs opened (under temporary names) for `base_model`'s bodies (the model of `file`,
// with or without a base); errors: the CSV and the HDF5 file have the error bars. `input` names
// IN in the bag's stamp error; `about`: the HDF5 file's attributes.
void open_outputs(const BagOutputs& o, const std::string& input, const mbk::ModelFile& file,
                  const mbk::Model& base_model, const std::string& base_frame, bool errors,
                  H5Attributes about, Outputs& out) {
  out.input = input;
  const std::vector<std::string>& missing = file.missing_segments;
  if (!o.out_bag.empty()) {
    out.bag_file = std::make_unique<OutputFile>(o.out_bag);
    out.bag = std::make_unique<BagOutput>(out.bag_file->writing(), file.model, o.frame_prefix,
                                          base_frame, base_model, missing);
  }
  std::vector<mbk::EulerOrder> orders;  // --angles', per body
  if (!o.angles.empty()) orders = mbk::angle_orders(base_model, o.angles);
  if (!o.out_csv.empty()) {
    out.csv_file = std::make_unique<OutputFile>(o.out_csv);
    mbk::TidyCsvExtras extras;
    extras.body_axes = o.body_axes;
    extras.angles = orders;
    out.csv = std::make_unique<mbk::TidyCsvWriter>(out.csv_file->writing(), base_model, errors,
                                                   missing.empty() ? "system" : "system_incomplete",
                                                   extras);
  }
  if (!o.out_h5.empty()) {
    out.h5_file = std::make_unique<OutputFile>(o.out_h5);
    about.frame = base_frame.empty() ? file.model.frame : base_frame;
    about.system = missing.empty() ? "system" : "system_incomplete";
    out.h5 =
        std::make_unique<H5Output>(out.h5_file->writing(), o.out_h5, base_model,
                                   file.model.coordinate_names, about, errors, o.h5_compression);
  }
  if (!o.out_mot.empty()) {
    out.mot_file = std::make_unique<OutputFile>(o.out_mot);
    MotColumns columns;  // without --angles: 1-2-3 (XYZ) for every body
    columns.angles = orders.empty() ? std::vector<mbk::EulerOrder>(base_model.bodies.size(),
                                                                   mbk::EulerOrder::kXYZ)
                                    : orders;
    columns.coordinates = o.mot_coordinates;
    out.mot = std::make_unique<MotOutput>(out.mot_file->writing(), o.out_mot, file.model,
                                          base_model, columns);
  }
  out.base_model = &base_model;
}

// Rows computed per OfflineStream chunk: a few blocks, small beside a long recording.
constexpr int kStreamChunkRows = 8192;

// The rows of the streamed path kept in memory for the passes after the first: up to this many
// bytes (about 26,000 samples of 37 coordinates); a longer recording is read again for each.
constexpr std::size_t kKeptRowBytes = std::size_t{16} << 20;

// The streamed path's input: its accepted rows (RecordingBuilder's sink), handed in order to each
// pass. The first pass reads the input and keeps the rows (up to kKeptRowBytes); the later passes
// replay them, or read the input again when it was longer. Reads of a bag: two when its rows fit
// (read_bag's check in a child process, then the first pass), else one more per later pass (the
// passes: the survey; the stamps' grid check, and the survey again when they are moved onto the
// grid; with jittered stamps, the stamps once more; "auto"'s choice; the computing); of a CSV or
// BVH file, one when its rows fit (a BVH input that is the model file: none, read_input).
class InputRows {
 public:
  using Sink = mbk::RecordingBuilder::RowSink;
  explicit InputRows(const InputReading& reading)
      : reading_(reading), kept_(reading.file.model.nq, kKeptRowBytes) {}
  // Every row to `sink`; the first pass's unreadable messages go to `s`.
  void pass(const Sink& sink, BagSummary& s) {
    if (read_ && kept_.complete()) return replay(sink);
    const bool first = !read_;
    mbk::RecordingBuilder builder(reading_.file.model);
    builder.stream_to([&](double t, const double* p, const double* v, const std::uint8_t* g) {
      if (first) kept_.keep(t, p, v, g);
      sink(t, p, v, g);
    });
    BaseOdometry unused;
    read_input(reading_, builder, unused, s, read_);
    builder.finish();  // every coordinate named, or the error
    if (!first) return;
    read_ = true;
    log_ = builder.log();
    samples_read_ = builder.samples_read();
    stamp_rounding_ = builder.stamp_rounding();
    time_origin_ = builder.time_origin();
  }
  // The reading's drops and notes (later passes read the same), and the samples read.
  mbk::DropLog& log() { return log_; }
  long samples_read() const { return samples_read_; }
  double stamp_rounding() const { return stamp_rounding_; }  // RecordingBuilder's
  double time_origin() const { return time_origin_; }        // RecordingBuilder's

 private:
  void replay(const Sink& sink) const {
    const std::size_t rows = kept_.rows();
    mbk::Progress bar("computing", reading_.progress);
    for (std::size_t r = 0; r < rows; ++r) {
      if (r % 1024 == 0) bar.update(static_cast<long>(r), static_cast<long>(rows));
      const mbk::KeptRows::Row row = kept_.row(r);
      sink(row.t, row.position, row.velocity, row.given);
    }
    bar.finish();
  }

  const InputReading reading_;
  bool read_ = false;
  mbk::KeptRows kept_;
  mbk::DropLog log_;
  long samples_read_ = 0;
  double stamp_rounding_ = 0, time_origin_ = 0;
};

// The bounded-memory path (offline/offline_stream.h): a first pass surveys the input, "auto"
// chooses its windows in a second, the last computes and writes the rows (InputRows: the input
// read once when its rows fit in kKeptRowBytes). False, with nothing written, when the
// recording needs the whole-recording path (a coordinate in some samples only).
// `about`: the HDF5 file's attributes (open_outputs).
bool run_streamed(const InputReading& reading, const BagOutputs& o, const BagComputing& c,
                  const H5Attributes& about, const mbk::OfflineEstimator& estimator,
                  mbk::OfflineReach reach, BagSummary& s) {
  const auto wall = Clock::now();
  const mbk::Model& model = reading.file.model;
  InputRows input(reading);
  const bool intervals = c.max_gap <= 0 || estimator.automatic;
  mbk::RecordingSurvey survey(model.nq, intervals);
  mbk::StampGridFit grid_fit;
  input.pass(
      [&](double t, const double*, const double*, const std::uint8_t* given) {
        survey.add(t, given);
        grid_fit.add(t);
      },
      s);
  if (!survey.streamable()) return false;
  if (grid_fit.fit())
    input.pass(
        [&](double t, const double*, const double*, const std::uint8_t*) { grid_fit.check(t); }, s);
  grid_fit.set_rounding(input.stamp_rounding());
  s.grid = grid_fit.grid();
  const mbk::StampGrid& grid = s.grid;  // every later pass sees the grid's times
  if (grid.moves) {
    survey = mbk::RecordingSurvey(model.nq, intervals);
    input.pass([&](double t, const double*, const double*,
                   const std::uint8_t* given) { survey.add(grid.snap(t), given); },
               s);
  }
  while (!survey.finish_pass())  // jittered stamps: the exact median interval
    input.pass([&](double t, const double*, const double*,
                   const std::uint8_t*) { survey.add_stamp(grid.snap(t)); },
               s);
  s.max_gap = c.max_gap > 0 ? c.max_gap : survey.default_max_gap();
  const int threads = c.threads > 0 ? c.threads : mbk::default_thread_count();
  mbk::WholeRecording whole;
  whole.velocity_everywhere = survey.velocity_everywhere;
  if (estimator.automatic) {  // the whole recording's choices, and the estimating pass's reach
    mbk::AutoChoosePass choose(model, survey, s.max_gap, kStreamChunkRows, threads);
    choose.set_stamp_grid(grid);
    input.pass([&](double t, const double* p, const double* v,
                   const std::uint8_t*) { choose.add(grid.snap(t), p, v); },
               s);
    whole = choose.finish(reach);
  }
  Outputs out;
  open_outputs(o, reading.in.input, reading.file, model, "", estimator.automatic, about, out);
  out.set_time_origin(input.time_origin());
  mbk::OfflineStream stream(
      model, estimator, reach, s.max_gap, std::move(whole), threads, kStreamChunkRows,
      [&](const mbk::OfflineRow& row) { take(row, out, input.log(), s.written); });
  stream.set_stamp_grid(grid);
  stream.set_time_origin(input.time_origin());
  stream.set_formatter(out.formatter());
  stream.set_body_errors((out.csv || out.h5) && estimator.automatic);
  std::unique_ptr<SampleErrorsFile> sample_errors;
  const bool sides = estimator.automatic && has_side_files(o.out_csv);
  if (out.csv && sides) {
    sample_errors =
        std::make_unique<SampleErrorsFile>(errors_path(o.out_csv, ".sample_errors.csv"), model);
    stream.set_chunk_hook([&](const mbk::OfflineStates& states, const mbk::Recording& piece,
                              int begin,
                              int end) { sample_errors->write(piece, states, begin, end); });
  }
  input.pass([&](double t, const double* p, const double* v,
                 const std::uint8_t* g) { stream.add(t, p, v, g); },
             s);
  stream.finish();  // the reading's progress bar is the computing's
  s.read = input.samples_read();
  s.log = input.log();
  s.threads = stream.threads();
  s.compute_seconds = stream.seconds().compute;
  const auto t_close = Clock::now();
  out.close();
  s.errors = stream.error_summary();
  if (sample_errors && !s.errors.empty()) {
    write_errors(errors_path(o.out_csv), s.errors);
    sample_errors->commit();
  }
  s.write_seconds = stream.seconds().use + since(t_close);
  s.read_seconds = std::max(0.0, since(wall) - s.write_seconds);
  return true;
}

}  // namespace

std::vector<NamedFile> output_files(const BagOutputs& o) {
  std::vector<NamedFile> files;
  if (!o.out_bag.empty()) files.push_back({"--out", o.out_bag});
  if (!o.out_csv.empty()) files.push_back({"--csv", o.out_csv});
  if (!o.out_h5.empty()) files.push_back({"--h5", o.out_h5});
  if (!o.out_mot.empty()) files.push_back({"--mot", o.out_mot});
  return files;
}

BagSummary run_bag(const BagOptions& o) {
  const auto wall = Clock::now();
  const mbk::OfflineEstimator estimator = mbk::make_offline_estimator(
      o.estimator.empty() ? mbk::default_offline_estimator() : o.estimator);
  refuse_same_files({{"the input", o.input}, {"--model", o.model}},
                    written_files(o, o.other_outputs, estimator.whole_series()));
  BagSummary s;
  const mbk::ModelFile file = load(o.model, o.bvh);
  const mbk::Model& model = file.model;
  s.estimator = estimator.name;
  if (!o.base_odometry.empty() && (ends_with(o.input, ".csv") || mbk::is_bvh_file(o.input)))
    throw std::invalid_argument("--base-odometry needs a bag input");
  // In bounded memory when the estimator says how far it reaches; else (or for a recording with
  // joint_accelerations, a floating base, a coordinate in some samples only) all of it at once.
  mbk::OfflineReach reach;
  const bool may_stream = o.base_odometry.empty() && o.joint_accelerations.empty() &&
                          (estimator.automatic || mbk::offline_reach(estimator, reach));
  const InputReading reading{o, file, o.bvh.scale, file.bvh && o.input == o.model, o.progress};
  H5Attributes about;  // what the HDF5 file says of its run (its frame and system: open_outputs)
  about.model_file = o.model, about.input = o.input, about.estimator = estimator.name;
  if (may_stream && run_streamed(reading, o, o, about, estimator, reach, s)) {
    s.wall_seconds = since(wall);
    return s;
  }
  mbk::RecordingBuilder builder(model);
  BaseOdometry base;
  read_input(reading, builder, base, s, may_stream);
  const mbk::Recording rec = builder.finish();
  s.grid = rec.grid;
  s.read = builder.samples_read();
  s.log = builder.log();
  s.read_seconds = since(wall);
  const bool floating = !o.base_odometry.empty();
  if (floating && base.samples.empty())
    throw std::invalid_argument(o.input + ": no usable message on '" + o.base_odometry + "'");
  // With a base, body_kinematics and the CSV list the node's layout (the model is not copied
  // without one).
  std::unique_ptr<const mbk::FloatingBase> with_base;
  if (floating)
    with_base = std::make_unique<const mbk::FloatingBase>(mbk::floating_base(
        model, std::move(base.samples), base.frame, estimator, o.max_gap, rec.grid));
  mbk::OfflineBatch batch(model, rec, estimator, o.max_gap, floating ? &with_base->track : nullptr,
                          o.threads > 0 ? o.threads : mbk::default_thread_count());
  s.max_gap = batch.max_gap();
  s.threads = batch.threads();
  Outputs out;
  const mbk::Model& base_model = floating ? with_base->layout : model;
  // The error bars' columns with auto (in the model's frame: not with a base).
  open_outputs(o, o.input, file, base_model, base.frame, estimator.whole_series() && !floating,
               about, out);
  out.set_time_origin(rec.origin);
  out.floating = floating;
  if (floating) out.base_data = std::make_unique<mbk::Data<double>>(base_model);
  batch.set_formatter(out.formatter());
  batch.set_body_errors((out.csv || out.h5) && estimator.whole_series() && !floating);
  compute_and_write(batch, model, rec.rows(), out, o.progress, s);
  s.errors = batch.error_summary();
  if (has_side_files(o.out_csv) && !s.errors.empty()) {
    write_errors(errors_path(o.out_csv), s.errors);
    SampleErrorsFile sample_errors(errors_path(o.out_csv, ".sample_errors.csv"), model);
    sample_errors.write(rec, batch.states(), 0, rec.rows());
    sample_errors.commit();
  }
  s.wall_seconds = since(wall);
  return s;
}

}  // namespace mbk_offline
