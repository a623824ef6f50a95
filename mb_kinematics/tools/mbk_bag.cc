// mbk_bag: `mbk bag` (mbk runs it, so that mbk itself stays free of ROS libraries).
//   mbk bag IN.bag|IN.csv --model FILE [--out OUT.bag] [--csv OUT.csv] [--joint-states TOPIC]
//       [--joint-accelerations TOPIC] [--base-odometry TOPIC] [--estimator NAME]
//       [--frame-prefix P] [--max-gap S] [--threads N] [--start-time S] [--summary-json FILE]
//   mbk bag WALK.bvh [--model FILE] [--scale M] [--body-mass KG] [--sex male|female] ...
#include <console_bridge/console.h>

#include <iostream>
#include <new>
#include <stdexcept>
#include <system_error>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/offline/memory_cap.h"
#include "mb_kinematics/offline/progress.h"
#include "mb_kinematics/offline/temporary_files.h"
#include "mb_kinematics/tools/bag_cli.h"
#include "mb_kinematics/tools/bag_summary_json.h"

namespace {

// A run that stopped with `error`: its one line on stderr, and --summary-json's record of it
// (nothing when that cannot be written either: the line still says what happened). Exit 1.
int fail(const mbk_offline::BagCommandLine& options, const std::string& error) {
  if (!options.summary_json.empty()) {
    try {
      mbk_offline::write_summary_json(options.summary_json,
                                      mbk_offline::format_failure_json(options, error));
    } catch (const std::exception&) {
    }
  }
  std::cerr << "mbk: error: " << mbk::printable(error) << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  // librosbag's own messages on damaged records ("Error: Received an invalid TCPROS header")
  // would break the one-line format: what it cannot read is counted and named in the summary.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  mbk_offline::remove_temporaries_on_signals();  // an interrupted run leaves no partial file
  mbk_offline::BagCommandLine options;
  double cap = 0;
  try {
    options = mbk_offline::parse_bag_options(argc, argv);
    cap = options.max_memory > 0 ? options.max_memory : mbk::default_memory_cap_gib();
    mbk::cap_memory(cap);
    if (options.help) {
      std::cout << mbk_offline::bag_usage();
      return 0;
    }
    options.progress = mbk::stderr_is_terminal();
    const mbk_offline::BagSummary summary = mbk_offline::run_bag(options);
    std::cerr << mbk_offline::format_summary(summary, options.verbose);
    if (!options.summary_json.empty())
      mbk_offline::write_summary_json(options.summary_json,
                                      mbk_offline::format_summary_json(options, summary));
    return mbk_offline::exit_status(summary);  // 2: partial (README "Recorded data")
  } catch (const std::bad_alloc&) {            // the cap, not the kernel, ended the run
    return fail(options, mbk::memory_cap_error(cap));
  } catch (const std::system_error& e) {  // no room for a thread's stack under the cap
    const bool cap_reached = e.code() == std::errc::resource_unavailable_try_again;
    return fail(options, cap_reached ? mbk::memory_cap_error(cap) : e.what());
  } catch (const std::exception& e) {
    return fail(options, e.what());
  }
}
