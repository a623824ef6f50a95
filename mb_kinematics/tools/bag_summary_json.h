// `mbk bag --summary-json FILE`: the run's summary as one JSON object, for programs (mbk batch's
// summary.csv) rather than people: the input and outputs, the status, the samples read, written
// and dropped by cause, the estimator and its noise level, the seconds, or the one-line error.
#pragma once

#include <string>

#include "mb_kinematics/offline/bag_command.h"

namespace mbk_offline {

// {"input": ..., "outputs": [...], "status": "ok" | "partial", "read": n, "written": n,
//  "dropped": n, "drops": {cause: n}, "unreadable": n, "estimator": ..., "noise_level": x or
//  null, "max_gap": s, "seconds": s, "error": ""} (status by exit_status: 0 ok, 2 partial;
//  a partial run's "error" says why: unreadable messages, nothing written).
std::string format_summary_json(const BagOptions& options, const BagSummary& summary);

// The same object for a run that stopped with `error`: "status": "failed", counts 0.
std::string format_failure_json(const BagOptions& options, const std::string& error);

// Writes `text` to `path`, replaced only when whole (output_file.h).
void write_summary_json(const std::string& path, const std::string& text);

}  // namespace mbk_offline
