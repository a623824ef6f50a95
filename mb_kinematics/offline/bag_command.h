// mbk bag: the kinematics of every sample of a recording (a rosbag, a trajectory CSV or a BVH
// file's motion) into a bag and/or a tidy CSV, with zero-phase derivative estimates
// (doc/recorded_data.md).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "mb_kinematics/estimation/stamp_grid.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk_offline {

struct BagOptions {
  std::string input;         // .bag, .csv or .bvh
  std::string model;         // a .bvh input's own skeleton when empty
  mbk::BvhModelOptions bvh;  // --scale, --body-mass, --sex: a .bvh model's
  std::string out_bag, out_csv;
  std::string summary_json;  // --summary-json: the summary for programs (bag_summary_json.h)
  std::string joint_states = "/joint_states";
  std::string joint_accelerations;
  std::string base_odometry;  // nav_msgs/Odometry of a floating base (core/floating_base.h)
  std::string estimator;      // empty: the default
  std::string frame_prefix;
  double max_gap = 0;     // seconds; 0: 5 x the median interval
  double start_time = 0;  // seconds added to every time of a .csv or .bvh input
  bool progress = false;  // draw a progress bar on stderr
  int threads = 0;        // computing threads; 0: one per CPU (default_thread_count)
  double max_memory = 0;  // --max-memory GiB of address space (offline/memory_cap.h); 0: default
  bool verbose = false;   // --verbose: the summary with every coordinate's error bars
  bool help = false;      // --help: print the usage, nothing else
};

struct BagSummary {
  long read = 0, written = 0;
  mbk::DropLog log;
  long unreadable = 0;             // messages skipped because they could not be read
  std::string unreadable_example;  // the first of them, and why
  // compute_seconds: summed over the computing threads, which run while this thread writes.
  double read_seconds = 0, compute_seconds = 0, write_seconds = 0, wall_seconds = 0;
  int threads = 1;
  std::string estimator;
  double max_gap = 0;
  std::vector<mbk::CoordinateError> errors;  // "auto": each coordinate's error bars
  mbk::StampGrid grid;  // the joint states' stamps on a uniform grid (estimation/stamp_grid.h)
};

// Throws std::invalid_argument (bad options, model, input) with a one-line message.
BagSummary run_bag(const BagOptions& options);

// mbk bag's exit status after a run: 0 when every sample read was written or dropped for a
// counted reason; 2 when some message could not be read or nothing was written (partial).
int exit_status(const BagSummary& s);

// The summary as printed at the end: samples, drops, the estimator, the noise level and the
// worst error bar; `verbose` adds every coordinate's error bars and the times.
std::string format_summary(const BagSummary& s, bool verbose = false);

// `mbk bag`'s usage (--help).
const char* bag_usage();

// Parses `mbk bag IN --model F ...` (argv[0] is "mbk", argv[1] "bag"); throws
// std::invalid_argument for a wrong command line.
BagOptions parse_bag_options(int argc, char** argv);

}  // namespace mbk_offline
