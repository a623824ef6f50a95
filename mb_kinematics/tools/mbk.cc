// mbk: the command-line tool (doc/method.md 8).
//   mbk tables (--lower 0,1,2,... | --model FILE) [--csv]
//   mbk eval --model FILE [--state STATE.json|- | --frame N]
//       [--method recursive|partial_velocity] [--partial-velocities] [--body-axes]
//       [--relative]   (-: standard input)
//   FILE: .urdf, .yaml or .bvh (with [--scale M] [--body-mass KG] [--sex male|female])
//   mbk urdf --model SCENE.yaml [--name ROBOT] [--display]   (a scene as URDF: the equivalent
//       kinematics for KDL and robot_state_publisher, or with --display a link per body for
//       rviz's RobotModel beside a node that runs the scene)
//   mbk bag IN.bag|IN.csv --model FILE [--out OUT.bag] [--csv OUT.csv] ...   (runs mbk_bag, beside
//       mbk, which links the ROS libraries that mbk itself does without)
//   mbk batch INPUT... --out-dir DIR [--jobs N] [--scheduler tcp://HOST:PORT] ...   (runs
//       mbk_batch, the Python package's mb_kinematics.batch: mbk bag over a collection)
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/estimation/offline_estimator.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/lower_body_text.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/io/state_json.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/offline/bvh_recording.h"

namespace {

const char kTablesUsage[] = "usage: mbk tables (--lower 0,1,2,... | --model FILE) [--csv]\n";
const char kEvalUsage[] =
    "usage: mbk eval --model FILE [--state STATE.json | --frame N]\n"
    "                [--method recursive|partial_velocity] [--partial-velocities]\n"
    "                [--body-axes] [--relative]\n";
const char kUrdfUsage[] = "usage: mbk urdf --model SCENE.yaml [--name ROBOT] [--display]\n";
const char kFileUsage[] =
    "   FILE: .urdf, .yaml or .bvh; a .bvh also takes [--scale M] (metres per file unit)\n"
    "         [--body-mass KG] [--sex male|female] [--segments MAP.yaml]\n"
    "         [--anthropometry de_leva|dempster]\n";

const char kUsage[] =
    "usage: mbk tables (--lower 0,1,2,... | --model FILE) [--csv]\n"
    "       mbk eval --model FILE [--state STATE.json|- | --frame N]\n"
    "                [--method recursive|partial_velocity] [--partial-velocities]\n"
    "                [--body-axes] [--relative]\n"
    "       mbk urdf --model SCENE.yaml [--name ROBOT] [--display]\n"
    "       mbk bag IN.bag|IN.csv|WALK.bvh [--model FILE] OUTPUTS [OPTIONS]   (mbk bag --help)\n"
    "       mbk batch INPUT... --out-dir DIR [--jobs N] [--scheduler tcp://HOST:PORT]\n"
    "           [--model FILE] [--bag] [--csv] [mbk bag's options]   (mbk batch --help)\n"
    "   FILE: .urdf, .yaml or .bvh; a .bvh also takes [--scale M] (metres per file unit)\n"
    "         [--body-mass KG] [--sex male|female] [--segments MAP.yaml]\n"
    "         [--anthropometry de_leva|dempster]\n"
    "   mbk COMMAND --help: that command's usage\n";

// `mbk COMMAND --help`'s text; "" for a command mbk does not have.
std::string command_usage(const std::string& command) {
  if (command == "tables") return std::string(kTablesUsage) + kFileUsage;
  if (command == "eval") return std::string(kEvalUsage) + kFileUsage;
  if (command == "urdf") return kUrdfUsage;
  return "";
}

bool asks_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
  return false;
}

// A wrong command line: the usage follows the one-line error. Bad data gives the error alone.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Options of the form --name value, and the flags --csv, --display, --partial-velocities,
// --body-axes and --relative.
std::map<std::string, std::string> parse_options(int argc, char** argv) {
  std::map<std::string, std::string> options;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--csv" || arg == "--display" || arg == "--partial-velocities" ||
        arg == "--body-axes" || arg == "--relative") {
      options[arg] = "1";
    } else if ((arg == "--lower" || arg == "--model" || arg == "--state" || arg == "--method" ||
                arg == "--name" || arg == "--frame" || arg == "--scale" || arg == "--body-mass" ||
                arg == "--sex" || arg == "--segments" || arg == "--anthropometry") &&
               i + 1 < argc) {
      options[arg] = argv[++i];
    } else {
      throw UsageError("unknown or incomplete option '" + arg + "'");
    }
  }
  return options;
}

std::string option(const std::map<std::string, std::string>& options, const std::string& name) {
  const auto it = options.find(name);
  return it == options.end() ? "" : it->second;
}

// --scale, --body-mass, --sex, --segments and --anthropometry, for a .bvh model only.
mbk::BvhModelOptions bvh_options(const std::map<std::string, std::string>& options,
                                 const std::string& path) {
  const bool given = options.count("--scale") || options.count("--body-mass") ||
                     options.count("--sex") || options.count("--frame") ||
                     options.count("--segments") || options.count("--anthropometry");
  if (given && !mbk::is_bvh_file(path))
    throw UsageError(
        "--scale, --body-mass, --sex, --segments, --anthropometry and --frame apply to a .bvh "
        "model only");
  return mbk::bvh_model_options(option(options, "--scale"), option(options, "--body-mass"),
                                option(options, "--sex"), option(options, "--segments"),
                                option(options, "--anthropometry"));
}

void print_warnings(const mbk::Model& model) {
  for (const std::string& warning : model.warnings)
    std::cerr << "mbk: warning: " << mbk::printable(warning) << "\n";
}

// FILE, read once; what the loader let through (e.g. inertias that are not physical) is printed
// once on stderr.
mbk::ModelFile load(const std::map<std::string, std::string>& options) {
  const std::string path = options.at("--model");
  mbk::ModelFile file = mbk::read_model_file(path, bvh_options(options, path));
  print_warnings(file.model);
  return file;
}

// Frame N of the BVH model file as the state: its coordinates, velocities and accelerations
// from the offline zero-phase estimator over the whole motion (mbk bag's, for that frame).
mbk::JointState<double> frame_state(const std::map<std::string, std::string>& options,
                                    const mbk::ModelFile& file) {
  const std::string path = options.at("--model"), text = options.at("--frame");
  char* end = nullptr;
  const long frame = std::strtol(text.c_str(), &end, 10);
  if (*end != '\0' || text.empty() || frame < 0 || frame > (1L << 30))
    throw UsageError("--frame needs a frame number from 0, not '" + text + "'");
  return mbk::bvh_frame_state(*file.bvh, file.model, bvh_options(options, path).scale,
                              static_cast<int>(frame), mbk::default_offline_estimator());
}

int tables(const std::map<std::string, std::string>& options) {
  std::vector<int> lower;
  std::vector<std::string> names;
  if (options.count("--lower") == options.count("--model"))
    throw UsageError("tables needs exactly one of --lower and --model");
  if (options.count("--lower")) {
    lower = mbk::parse_lower_body_array(options.at("--lower"));
    mbk::validate_lower_body_array(lower);
  } else {
    const mbk::Model model = load(options).model;
    lower = model.lower_body_array();
    for (int k = 1; k <= model.body_count(); ++k) names.push_back(model.bodies[k].name);
  }
  if (options.count("--csv"))
    mbk::write_lower_body_csv(std::cout, lower);
  else
    mbk::write_lower_body_table(std::cout, lower, names);
  return 0;
}

// What the state came from, for an error: the STATE.json path, "standard input" for "-".
std::string state_source(const std::map<std::string, std::string>& options) {
  const std::string path = option(options, "--state");
  return path.empty() ? "state" : path == "-" ? "standard input" : path;
}

int eval(const std::map<std::string, std::string>& options) {
  if (!options.count("--model")) throw UsageError("eval needs --model FILE");
  if (options.count("--state") && options.count("--frame"))
    throw UsageError("eval takes --state or --frame, not both");
  const mbk::ModelFile file = load(options);  // --frame: a .bvh file (bvh_options)
  const mbk::Model& model = file.model;
  const mbk::JointState<double> state = options.count("--state")
                                            ? mbk::read_state_file(model, options.at("--state"))
                                        : options.count("--frame") ? frame_state(options, file)
                                                                   : mbk::default_state(model);
  const std::string problem = mbk::check_state(model, state);  // NaN/Inf, |e| ~ 0, overflow
  if (!problem.empty()) throw std::invalid_argument(state_source(options) + ": " + problem);
  mbk::Data<double> data(model);
  const std::string method = options.count("--method") ? options.at("--method") : "recursive";
  if (method != "recursive" && method != "partial_velocity")
    throw UsageError("unknown --method '" + method + "'");
  const bool partials = options.count("--partial-velocities");
  std::unique_ptr<mbk::PartialVelocities<double>> pv;  // O(N * depth): only when used
  if (method == "partial_velocity" || partials) {
    pv = std::make_unique<mbk::PartialVelocities<double>>(model);
    mbk::Data<double> scratch(model);
    mbk::partial_velocity_kinematics(model, state, *pv, method == "recursive" ? scratch : data);
  }
  if (method == "recursive") mbk::forward_kinematics(model, state, data);
  mbk::SystemKinematics<double> system;
  mbk::system_kinematics(model, data, system);
  mbk::EvalExtras extra;
  extra.body_axes = options.count("--body-axes");
  extra.relative = options.count("--relative");
  std::cout << mbk::format_eval_json(model, data, &system, partials ? pv.get() : nullptr,
                                     file.missing_segments, extra);
  return 0;
}

int urdf(const std::map<std::string, std::string>& options) {
  if (!options.count("--model")) throw UsageError("urdf needs --model FILE");
  const mbk::Model model = load(options).model;
  std::cout << mbk::write_urdf(
      model, options.count("--name") ? options.at("--name") : "scene",
      options.count("--display") ? mbk::UrdfStyle::kDisplay : mbk::UrdfStyle::kEquivalent);
  return 0;
}

// mbk's own directory, with the trailing '/'.
std::string own_directory(char** argv) {
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  const std::string path = n > 0 ? std::string(self, n) : std::string(argv[0]);
  return path.substr(0, path.rfind('/') + 1);
}

// Replaces this process by mbk_bag from mbk's own directory, with the same arguments.
int exec_bag(char** argv) {
  const std::string path = own_directory(argv) + "mbk_bag";
  execv(path.c_str(), argv);
  throw std::runtime_error("cannot run " + path + " (is mb_kinematics built with rosbag?)");
}

// Replaces this process by mbk_batch from mbk's own directory with the arguments after
// "batch", the package's Python folder (devel or install space: lib/mb_kinematics/../../
// MBK_PYTHON_DIR) first on PYTHONPATH and that directory's mbk_bag as MBK_BAG.
int exec_batch(char** argv) {
  const std::string directory = own_directory(argv);
  std::string python_path = directory + "../../" MBK_PYTHON_DIR;
  if (const char* earlier = std::getenv("PYTHONPATH")) python_path += std::string(":") + earlier;
  setenv("PYTHONPATH", python_path.c_str(), 1);
  setenv("MBK_BAG", (directory + "mbk_bag").c_str(), 0);
  const std::string path = directory + "mbk_batch";
  argv[1] = argv[0];
  execv(path.c_str(), argv + 1);
  throw std::runtime_error("cannot run " + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  try {
    const std::string command = argv[1];
    if (command == "bag") return exec_bag(argv);
    if (command == "batch") return exec_batch(argv);
    if (asks_help(argc, argv) && !command_usage(command).empty()) {
      std::cout << command_usage(command);
      return 0;
    }
    const auto options = parse_options(argc, argv);
    if (command == "tables") return tables(options);
    if (command == "eval") return eval(options);
    if (command == "urdf") return urdf(options);
    throw UsageError("unknown command '" + command + "'");
  } catch (const UsageError& e) {
    std::cerr << "mbk: error: " << mbk::printable(e.what()) << "\n" << kUsage;
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mbk: error: " << mbk::printable(e.what()) << "\n";
    return 1;
  }
}
