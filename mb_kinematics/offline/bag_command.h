// mbk bag: the kinematics of every sample of a recording (a rosbag, a trajectory CSV or a BVH
// file's motion) into a bag and/or a tidy CSV, with zero-phase derivative estimates
// (doc/recorded_data.md).
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/estimation/stamp_grid.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/offline/bag_input.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk_offline {

// A file by what names it ("--csv", "the input"), for messages.
struct NamedFile {
  std::string name, path;
};

// What a run reads: IN and, of a bag, its topics (bag_input.h).
struct BagInput : BagTopics {
  std::string input;      // .bag, .csv or .bvh
  double start_time = 0;  // seconds added to every time of a .csv or .bvh input
};

// What a run writes: OUT.bag, OUT.csv, OUT.h5 and/or OUT.mot.
struct BagOutputs {
  std::string out_bag, out_csv;
  std::string out_h5;        // --h5 (offline/h5_output.h)
  std::string out_mot;       // --mot: OpenSim Storage (offline/mot_output.h)
  int h5_compression = 0;    // --h5-compression: deflate level 0-9
  std::string frame_prefix;  // of the bag's frames (messages/frames.h)
  bool body_axes = false;    // --body-axes: the CSV's segment-frame columns (io/tidy_csv.h)
  // --angles ORDER|FILE.yaml: the orders of the CSV's and OUT.mot's joint angles
  std::string angles;
  // --mot-coordinates: OUT.mot's joint coordinates, after the joint angles
  bool mot_coordinates = false;
};

// How a run computes: the estimator, the gaps it does not bridge, the threads.
struct BagComputing {
  std::string estimator;  // empty: the default
  double max_gap = 0;     // seconds; 0: 5 x the median interval
  int threads = 0;        // computing threads; 0: one per CPU (default_thread_count)
};

// A run of mbk bag (mb_kinematics/tools/bag_cli.h makes it from the command line): its input,
// its outputs, and how the kinematics are computed. The inner steps take their group only.
struct BagOptions : BagInput, BagOutputs, BagComputing {
  std::string model;         // a .bvh input's own skeleton when empty
  mbk::BvhModelOptions bvh;  // --scale, --body-mass, --sex: a .bvh model's
  bool progress = false;     // draw a progress bar on stderr
  // Files the caller writes besides the outputs (mbk bag's --summary-json): refused, as the
  // outputs are, when one is an input or another output.
  std::vector<NamedFile> other_outputs;
};

// The files a run writes (but the error bars' side files): --out, --csv, --h5, --mot, in that
// order.
std::vector<NamedFile> output_files(const BagOutputs& o);

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

}  // namespace mbk_offline
