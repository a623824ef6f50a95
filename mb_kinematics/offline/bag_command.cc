#include "mb_kinematics/offline/bag_command.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/offline_estimator.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/offline_kinematics.h"
#include "mb_kinematics/io/progress.h"
#include "mb_kinematics/io/tidy_csv.h"
#include "mb_kinematics/io/trajectory_csv.h"
#include "mb_kinematics/offline/bag_input.h"
#include "mb_kinematics/offline/bag_output.h"

namespace mbk_offline {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool ends_with(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

bool finite(const mbk::Data<double>& d, int k) {
  return d.rotation[k].allFinite() && d.origin[k].allFinite() && d.mass_center[k].allFinite() &&
         d.omega[k].allFinite() && d.mass_center_velocity[k].allFinite() && d.alpha[k].allFinite() &&
         d.mass_center_acceleration[k].allFinite();
}

// The node's model rules: coordinate-derivative speeds (JointState velocities are q').
mbk::Model load(const std::string& path) {
  mbk::Model model = mbk::load_model_file(path);
  if (model.speeds != mbk::SpeedKind::kCoordinateDerivatives) {
    model.speeds = mbk::SpeedKind::kCoordinateDerivatives;
    mbk::finalize_model(model);
  }
  return model;
}

}  // namespace

BagOptions parse_bag_options(int argc, char** argv) {
  BagOptions o;
  const std::map<std::string, std::string*> values = {
      {"--model", &o.model},
      {"--out", &o.out_bag},
      {"--csv", &o.out_csv},
      {"--joint-states", &o.joint_states},
      {"--joint-accelerations", &o.joint_accelerations},
      {"--base-odometry", &o.base_odometry},
      {"--estimator", &o.estimator},
      {"--frame-prefix", &o.frame_prefix}};
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    auto it = values.find(arg);
    if (it != values.end() && i + 1 < argc) {
      *it->second = argv[++i];
    } else if (arg == "--max-gap" && i + 1 < argc) {
      char* end = nullptr;
      o.max_gap = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(o.max_gap >= 0))
        throw std::invalid_argument("--max-gap needs seconds >= 0, not '" + std::string(argv[i]) +
                                    "'");
    } else if (arg.rfind("--", 0) != 0 && o.input.empty()) {
      o.input = arg;
    } else {
      throw std::invalid_argument("unknown or incomplete option '" + arg + "'");
    }
  }
  if (o.input.empty()) throw std::invalid_argument("bag needs an input IN.bag or IN.csv");
  if (o.model.empty()) throw std::invalid_argument("bag needs --model FILE");
  if (o.out_bag.empty() && o.out_csv.empty())
    throw std::invalid_argument("bag needs --out OUT.bag and/or --csv OUT.csv");
  return o;
}

BagSummary run_bag(const BagOptions& o) {
  const auto wall = Clock::now();
  BagSummary s;
  const mbk::Model model = load(o.model);
  const mbk::OfflineEstimator estimator = mbk::make_offline_estimator(
      o.estimator.empty() ? mbk::default_offline_estimator() : o.estimator);
  s.estimator = estimator.name;
  // Read everything first: the centred estimates look ahead.
  mbk::RecordingBuilder builder(model);
  BaseOdometry base;
  if (!o.base_odometry.empty() && ends_with(o.input, ".csv"))
    throw std::invalid_argument("--base-odometry needs a bag input");
  {
    mbk::Progress bar("reading  ", o.progress);
    if (ends_with(o.input, ".csv")) {
      mbk::read_trajectory_csv(o.input, builder);
    } else {
      read_bag(o.input, {o.joint_states, o.joint_accelerations, o.base_odometry}, builder, base,
               [&](long done, long total) { bar.update(done, total); });
    }
  }
  const mbk::Recording rec = builder.finish();
  s.read = builder.samples_read();
  s.log = builder.log();
  s.read_seconds = since(wall);
  mbk::OfflineStates states(model, rec, estimator, o.max_gap);
  s.max_gap = states.max_gap();
  const bool floating = !o.base_odometry.empty();
  if (floating && base.samples.empty())
    throw std::invalid_argument(o.input + ": no usable message on '" + o.base_odometry + "'");
  std::vector<mbk::Vec3<double>> base_linear, base_angular;
  std::vector<int> base_valid;
  if (floating)
    mbk::base_accelerations(base.samples, estimator,
                            o.max_gap > 0 ? o.max_gap : mbk::default_max_gap([&] {
                              std::vector<double> t;
                              for (const auto& b : base.samples) t.push_back(b.t);
                              return t;
                            }()),
                            base_linear, base_angular, base_valid);
  mbk::BaseMotion motion;
  std::unique_ptr<BagOutput> bag;
  std::unique_ptr<mbk::TidyCsvWriter> csv;
  if (!o.out_bag.empty())
    bag = std::make_unique<BagOutput>(o.out_bag, model, o.frame_prefix, base.frame);
  if (!o.out_csv.empty()) csv = std::make_unique<mbk::TidyCsvWriter>(o.out_csv, model);
  mbk::JointState<double> state(model);
  mbk::Data<double> data(model);
  mbk::Progress bar("computing", o.progress);
  for (int r = 0; r < rec.rows(); ++r) {
    const auto t0 = Clock::now();
    const std::string where = "sample at t = " + std::to_string(rec.stamp[r]);
    std::string problem = states.state_at(r, state);
    if (!problem.empty()) {
      s.log.drop("too few samples for derivatives", where + ": " + problem);
      continue;
    }
    problem = mbk::check_state(model, state);  // NaN/Inf, |e| ~ 0, overflow
    if (!problem.empty()) {
      s.log.drop("state rejected (mbk::check_state)", where + ": " + problem);
      continue;
    }
    mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
    if (floating) {
      if (!mbk::interpolate_base(base.samples, base_linear, base_angular, rec.stamp[r], motion)) {
        s.log.drop("outside the base odometry's time span", where);
        continue;
      }
      mbk::apply_floating_base(motion, data);
    }
    bool ok = true;
    for (int k = 1; k <= model.body_count() && ok; ++k) ok = finite(data, k);
    if (!ok) {
      s.log.drop("kinematics not finite", where);
      continue;
    }
    const auto t1 = Clock::now();
    if (bag) bag->write(rec.stamp[r], state, data, floating ? &motion : nullptr);
    if (csv) csv->write(rec.stamp[r], data);
    ++s.written;
    s.compute_seconds += std::chrono::duration<double>(t1 - t0).count();
    s.write_seconds += since(t1);
    bar.update(r + 1, rec.rows());
  }
  bar.finish();
  const auto t_close = Clock::now();
  if (bag) bag->close();
  if (csv) csv->close();
  s.write_seconds += since(t_close);
  s.wall_seconds = since(wall);
  return s;
}

std::string format_summary(const BagSummary& s) {
  char line[256];
  std::string out;
  std::snprintf(
      line, sizeof line,
      "mbk bag: %ld samples read, %ld written, %ld dropped (estimator %s, gaps > %.3g s)\n", s.read,
      s.written, s.log.dropped(), s.estimator.c_str(), s.max_gap);
  out += line;
  for (const auto& d : s.log.drops)
    out += "  dropped " + std::to_string(d.second) + ": " + d.first +
           " (first: " + s.log.example.at(d.first) + ")\n";
  for (const auto& n : s.log.notes)
    out += "  note " + std::to_string(n.second) + " samples: " + n.first +
           " (first: " + s.log.example.at(n.first) + ")\n";
  const double rate = s.wall_seconds > 0 ? s.written / s.wall_seconds : 0;
  std::snprintf(line, sizeof line,
                "  wall %.3f s (%.0f samples/s): read %.3f s, compute %.3f s, write %.3f s\n",
                s.wall_seconds, rate, s.read_seconds, s.compute_seconds, s.write_seconds);
  out += line;
  return out;
}

}  // namespace mbk_offline
