// The temporary files of a run (output_file.h) removed when SIGINT, SIGTERM or SIGHUP ends it:
// their paths are recorded in a fixed table that the signal handler reads without allocating
// (unlink is async-signal-safe), then the signal's earlier action is restored and the signal
// raised again, so that the process ends as it would have.
#pragma once

#include <string>

namespace mbk_offline {

// Installs the handler for SIGINT, SIGTERM and SIGHUP (once; later calls do nothing), except for
// a signal the process ignores (started under nohup, say): that one stays ignored, and the run
// goes on to write its outputs.
void remove_temporaries_on_signals();

// Records `path` for removal on those signals: a slot to forget(), or -1 when the table is full
// or the path too long (the next run on that output then removes it: output_file.h).
int record_temporary(const std::string& path);
// Stops recording slot `slot` (from record_temporary; -1 does nothing).
void forget_temporary(int slot);

}  // namespace mbk_offline
