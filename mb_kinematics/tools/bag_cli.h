// `mbk bag`'s command line (mbk_bag): its options into the engine's run (offline/bag_command.h),
// its usage, the summary it prints and its exit status. A new option is a row of kOptions in
// bag_cli.cc (and, for a field the engine reads, a field of BagOptions); the usage and mbk batch
// take it from there.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/offline/bag_command.h"

namespace mbk_offline {

// The command line: the run, and what mbk bag does around it.
struct BagCommandLine : BagOptions {
  std::string summary_json;  // --summary-json: the summary for programs (bag_summary_json.h)
  double max_memory = 0;     // --max-memory GiB of address space (offline/memory_cap.h); 0: default
  bool verbose = false;      // --verbose: the summary with every coordinate's error bars
  bool help = false;         // --help: print the usage, nothing else
};

// Parses `mbk bag IN --model F ...` (argv[0] is "mbk", argv[1] "bag"); throws
// std::invalid_argument for a wrong command line. --summary-json's file is among the run's
// other_outputs (refused when it is an input or an output).
BagCommandLine parse_bag_options(int argc, char** argv);

// `mbk bag`'s usage (--help): every row of kOptions.
std::string bag_usage();

// Who takes an option of `mbk bag`: mbk batch gives it as given to every job, or to the jobs of
// .bvh inputs (a BVH model's options); or mbk bag alone (the model, the outputs, which mbk batch
// names itself, and the process's own: --max-memory, --verbose, --help).
enum class BagOptionUse { kEveryJob, kBvhJobs, kBagAlone };

// The rows of kOptions, for the usage, mbk batch (through the Python module) and their tests:
// each option's name, the value that follows it ("" for a flag) and who takes it.
struct BagOptionRow {
  std::string name, value;
  BagOptionUse use;
};
std::vector<BagOptionRow> bag_option_rows();

// Refuses (std::invalid_argument) an option among `given` that adds to outputs (columns:
// --body-axes to the CSV, --angles to the CSV and the OpenSim file, --mot-coordinates to the
// OpenSim file) when none of those is among `outputs` ("--csv", "--mot", ...): mbk bag's rule, and
// mbk batch's through the Python module. with_values: the message gives the outputs with their
// values
// ("give --csv OUT.csv", mbk bag's), else their names alone (mbk batch's --csv takes none).
void check_column_options(const std::vector<std::string>& given,
                          const std::vector<std::string>& outputs, bool with_values);

// The summary as printed at the end: samples, drops, the estimator, the noise level and the
// worst error bar; `verbose` adds every coordinate's error bars and the times.
std::string format_summary(const BagSummary& s, bool verbose = false);

// mbk bag's exit status after a run: 0 when every sample read was written or dropped for a
// counted reason; 2 when some message could not be read or nothing was written (partial).
int exit_status(const BagSummary& s);

}  // namespace mbk_offline
