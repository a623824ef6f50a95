#include "mb_kinematics/tools/bag_cli.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <vector>

#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/tools/error_bar_summary.h"

namespace mbk_offline {
namespace {

bool ends_with(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

// The command line as it is read: a .bvh model's options as text, checked once all are read;
// the options given, by name.
struct Reading {
  BagCommandLine line;
  std::string scale, body_mass, sex, segments, anthropometry;
  std::vector<std::string> given;
};

// `text` as a number, NaN when it is not one whole.
double number(const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  return *end == '\0' ? x : NAN;
}

// One option of `mbk bag`: its name, the value that follows it in the usage ("" for a flag), who
// takes it (bag_cli.h) and what it sets (a wrong value throws std::invalid_argument naming the
// option). A value option is given once at most. An option that adds to outputs (its columns)
// says what it adds and the outputs it needs, one at least (check_column_options).
struct Option {
  const char* name;
  const char* value;
  BagOptionUse use;
  void (*set)(Reading& r, const std::string& value);
  const char* adds = "";               // "adds columns to the CSV"
  std::array<const char*, 2> needs{};  // "--csv", "--mot": the outputs it adds to
  bool takes_value() const { return *value != '\0'; }
};

constexpr BagOptionUse kJob = BagOptionUse::kEveryJob, kBvh = BagOptionUse::kBvhJobs,
                       kOwn = BagOptionUse::kBagAlone;

const Option kOptions[] = {
    {"--model", "FILE", kOwn, [](Reading& r, const std::string& v) { r.line.model = v; }},
    {"--out", "OUT.bag", kOwn, [](Reading& r, const std::string& v) { r.line.out_bag = v; }},
    {"--csv", "OUT.csv", kOwn, [](Reading& r, const std::string& v) { r.line.out_csv = v; }},
    {"--h5", "OUT.h5", kOwn, [](Reading& r, const std::string& v) { r.line.out_h5 = v; }},
    {"--h5-compression", "0-9", kJob,
     [](Reading& r, const std::string& v) {
       char* end = nullptr;
       const long level = std::strtol(v.c_str(), &end, 10);
       if (v.empty() || *end != '\0' || level < 0 || level > 9)
         throw std::invalid_argument("--h5-compression needs a deflate level from 0 to 9, not '" +
                                     v + "'");
       r.line.h5_compression = static_cast<int>(level);
     }},
    {"--mot", "OUT.mot", kOwn, [](Reading& r, const std::string& v) { r.line.out_mot = v; }},
    {"--mot-coordinates",
     "",
     kJob,
     [](Reading& r, const std::string&) { r.line.mot_coordinates = true; },
     "adds columns to the OpenSim file",
     {"--mot"}},
    {"--summary-json", "FILE", kOwn,
     [](Reading& r, const std::string& v) { r.line.summary_json = v; }},
    {"--joint-states", "TOPIC", kJob,
     [](Reading& r, const std::string& v) { r.line.joint_states = v; }},
    {"--joint-accelerations", "TOPIC", kJob,
     [](Reading& r, const std::string& v) { r.line.joint_accelerations = v; }},
    {"--base-odometry", "TOPIC", kJob,
     [](Reading& r, const std::string& v) { r.line.base_odometry = v; }},
    {"--estimator", "NAME", kJob, [](Reading& r, const std::string& v) { r.line.estimator = v; }},
    {"--frame-prefix", "P", kJob,
     [](Reading& r, const std::string& v) { r.line.frame_prefix = v; }},
    {"--scale", "M", kBvh, [](Reading& r, const std::string& v) { r.scale = v; }},
    {"--body-mass", "KG", kBvh, [](Reading& r, const std::string& v) { r.body_mass = v; }},
    {"--sex", "male|female", kBvh, [](Reading& r, const std::string& v) { r.sex = v; }},
    {"--segments", "MAP.yaml", kBvh, [](Reading& r, const std::string& v) { r.segments = v; }},
    {"--anthropometry", "de_leva|dempster", kBvh,
     [](Reading& r, const std::string& v) { r.anthropometry = v; }},
    {"--body-axes",
     "",
     kJob,
     [](Reading& r, const std::string&) { r.line.body_axes = true; },
     "adds columns to the CSV",
     {"--csv"}},
    {"--angles",
     "ORDER|ORDERS.yaml",
     kJob,
     [](Reading& r, const std::string& v) {
       if (!ends_with(v, ".yaml") && !ends_with(v, ".yml"))
         mbk::euler_order_from_string(v);  // a bad order refused before anything is read
       r.line.angles = v;
     },
     "sets the joint angles of the CSV and the OpenSim file",
     {"--csv", "--mot"}},
    {"--max-gap", "S", kJob,
     [](Reading& r, const std::string& v) {
       r.line.max_gap = number(v);
       if (!(r.line.max_gap > 0))  // 0 is the default's mark: not a gap to give
         throw std::invalid_argument("--max-gap needs seconds > 0, not '" + v +
                                     "' (leave it out for 5 x the median sample interval)");
     }},
    {"--start-time", "S", kJob,
     [](Reading& r, const std::string& v) {
       r.line.start_time = number(v);
       if (!std::isfinite(r.line.start_time))
         throw std::invalid_argument("--start-time needs seconds, not '" + v + "'");
     }},
    {"--threads", "N", kJob,
     [](Reading& r, const std::string& v) {
       char* end = nullptr;
       const long n = std::strtol(v.c_str(), &end, 10);
       if (*end != '\0' || n < 1 || n > 1024)
         throw std::invalid_argument("--threads needs a count from 1 to 1024, not '" + v + "'");
       r.line.threads = static_cast<int>(n);
     }},
    {"--max-memory", "GIB", kOwn,
     [](Reading& r, const std::string& v) {
       r.line.max_memory = number(v);
       if (!(r.line.max_memory > 0) || !std::isfinite(r.line.max_memory))
         throw std::invalid_argument("--max-memory needs GiB > 0, not '" + v + "'");
     }},
    {"--verbose", "", kOwn, [](Reading& r, const std::string&) { r.line.verbose = true; }},
    {"--help", "", kOwn, [](Reading& r, const std::string&) { r.line.help = true; }},
    {"-h", "", kOwn, [](Reading& r, const std::string&) { r.line.help = true; }},
};

const Option* find_option(const std::string& name) {
  for (const Option& option : kOptions)
    if (name == option.name) return &option;
  return nullptr;
}

// The checks across options, once all are read.
void check(Reading& r) {
  BagCommandLine& o = r.line;
  if (o.input.empty()) throw std::invalid_argument("bag needs an input IN.bag, IN.csv or IN.bvh");
  if (o.model.empty() && mbk::is_bvh_file(o.input)) o.model = o.input;
  if (o.model.empty()) throw std::invalid_argument("bag needs --model FILE");
  if (!(r.scale + r.body_mass + r.sex + r.segments + r.anthropometry).empty() &&
      !mbk::is_bvh_file(o.model))
    throw std::invalid_argument(
        "--scale, --body-mass, --sex, --segments and --anthropometry apply to a .bvh model only");
  o.bvh = mbk::bvh_model_options(r.scale, r.body_mass, r.sex, r.segments, r.anthropometry);
  std::vector<std::string> outputs;
  for (const NamedFile& file : output_files(o)) outputs.push_back(file.name);
  check_column_options(r.given, outputs, true);
  if (outputs.empty())
    throw std::invalid_argument(
        "bag needs at least one of --out OUT.bag, --csv OUT.csv, --h5 OUT.h5, --mot OUT.mot");
  if (o.start_time != 0 && !ends_with(o.input, ".csv") && !mbk::is_bvh_file(o.input))
    throw std::invalid_argument("--start-time applies to a .csv or .bvh input, not a bag");
  if (!o.summary_json.empty()) o.other_outputs.push_back({"--summary-json", o.summary_json});
}

}  // namespace

BagCommandLine parse_bag_options(int argc, char** argv) {
  Reading r;
  std::set<std::string> given;  // value options: each once
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const Option* option = find_option(arg);
    if (option && (!option->takes_value() || i + 1 < argc)) {
      if (option->takes_value() && !given.insert(arg).second)
        throw std::invalid_argument(arg + " is given twice");
      r.given.push_back(arg);
      option->set(r, option->takes_value() ? argv[++i] : "");
      if (r.line.help) return r.line;  // the usage, whatever else is given
    } else if (arg.rfind("--", 0) != 0 && r.line.input.empty()) {
      r.line.input = arg;
    } else {
      throw std::invalid_argument("unknown or incomplete option '" + arg + "'");
    }
  }
  check(r);
  return r.line;
}

void check_column_options(const std::vector<std::string>& given,
                          const std::vector<std::string>& outputs, bool with_values) {
  const auto has = [](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  for (const Option& option : kOptions) {
    if (!option.needs[0] || !has(given, option.name)) continue;
    std::string give;
    bool found = false;
    for (const char* output : option.needs) {
      if (!output) break;
      found = found || has(outputs, output);
      give += (give.empty() ? "" : " or ") + std::string(output);
      if (with_values) give += std::string(" ") + find_option(output)->value;
    }
    if (!found)
      throw std::invalid_argument(std::string(option.name) + " " + option.adds + ": give " + give);
  }
}

std::vector<BagOptionRow> bag_option_rows() {
  std::vector<BagOptionRow> rows;
  for (const Option& option : kOptions) rows.push_back({option.name, option.value, option.use});
  return rows;
}

namespace {

// The usage's lines of options: `heading`, then every row of kOptions taken by `use`, wrapped.
std::string option_lines(const char* heading, BagOptionUse use) {
  constexpr std::size_t kWidth = 100;
  const std::string indent(7, ' ');
  std::string text = std::string("   ") + heading + "\n", line = indent;
  for (const Option& option : kOptions) {
    if (option.use != use) continue;
    const std::string item =
        std::string("[") + option.name + (option.takes_value() ? " " : "") + option.value + "]";
    if (line.size() > indent.size() && line.size() + 1 + item.size() > kWidth)
      text += line + "\n", line = indent;
    line += (line.size() > indent.size() ? " " : "") + item;
  }
  return text + line + "\n";
}

}  // namespace

std::string bag_usage() {
  return "usage: mbk bag IN.bag|IN.csv --model FILE OUTPUTS [OPTIONS]\n"
         "       mbk bag WALK.bvh [--model FILE] OUTPUTS [OPTIONS] [BVH OPTIONS]\n" +
         option_lines(
             "OUTPUTS (one at least; --body-axes with --csv, --angles with --csv or --mot,\n"
             "   --mot-coordinates with --mot), and the run's own:",
             BagOptionUse::kBagAlone) +
         option_lines("OPTIONS:", BagOptionUse::kEveryJob) +
         option_lines("BVH OPTIONS (a .bvh model's):", BagOptionUse::kBvhJobs) +
         "   --body-axes: omega, alpha, velocity, acceleration in each body's own axes\n"
         "   --angles: each body's Cardan/Euler angles relative to its lower body, ORDER one of\n"
         "             XYZ ... ZYZ, or a YAML file of body or joint name: ORDER (and default:)\n"
         "   --mot: the joint angles in degrees (--angles' orders, XYZ without it) as OpenSim\n"
         "          Storage; --mot-coordinates adds the joint coordinates\n"
         "   --verbose: every coordinate's error bars and the times in the summary\n"
         "   --max-memory: GiB of address space at most (default: 90 % of this machine's memory)\n"
         "   --summary-json FILE: the summary as JSON (also for a run that fails)\n";
}

std::string format_summary(const BagSummary& s, bool verbose) {
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
  if (s.grid.moves) {
    std::snprintf(line, sizeof line,
                  "  stamps on a uniform grid of %.9g s: differentiated at the grid's times, %.2g "
                  "s at most from the stamps (tolerance %.2g s)\n",
                  static_cast<double>(s.grid.period), s.grid.worst, s.grid.tolerance);
    out += line;
  }
  if (!verbose) out += mbk::error_bar_line(s.errors);
  if (verbose && !s.errors.empty())
    out +=
        "  error bars (noise level; median standard error of velocity, acceleration, medians to "
        "5e-4 relative):\n";
  for (const mbk::CoordinateError& e : verbose ? s.errors : std::vector<mbk::CoordinateError>{}) {
    std::snprintf(line, sizeof line, "    %s: noise %.2e; %.2e, %.2e\n",
                  mbk::printable(e.name).c_str(), e.noise, e.velocity_se, e.acceleration_se);
    out += line;
  }
  if (s.unreadable > 0)
    out += "  unreadable " + std::to_string(s.unreadable) +
           " messages, skipped: the output is partial (first: " + s.unreadable_example + ")\n";
  if (s.written == 0) out += "  nothing written\n";
  if (!verbose) return out;
  const double rate = s.wall_seconds > 0 ? s.written / s.wall_seconds : 0;
  std::snprintf(line, sizeof line,
                "  wall %.3f s (%.0f samples/s): read %.3f s, compute %.3f s (%d threads, summed; "
                "beside the writing), write %.3f s\n",
                s.wall_seconds, rate, s.read_seconds, s.compute_seconds, s.threads,
                s.write_seconds);
  out += line;
  return out;
}

int exit_status(const BagSummary& s) { return s.unreadable == 0 && s.written > 0 ? 0 : 2; }

}  // namespace mbk_offline
