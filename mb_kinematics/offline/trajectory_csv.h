// Trajectory CSV input (what mocap and biomechanics pipelines export): a header `time,<coordinate
// name>,...`, then one sample per line (time in seconds). An empty cell means the coordinate is
// not in that sample (it keeps its last value); `nan` cells drop the sample (counted). ROS-free.
#pragma once

#include <string>

#include "mb_kinematics/offline/recording.h"

namespace mbk {

// Adds every line of `path` to `builder`; lines may end in LF, CRLF or a lone CR, and a UTF-8
// byte-order mark may come first. Throws std::invalid_argument naming the file, line and column
// for what cannot be read (no `time` column first, a column named twice, a cell that is not a
// number, or has a NUL byte inside); a line
// with the wrong number of cells (e.g. a truncated last line) is dropped and counted.
void read_trajectory_csv(const std::string& path, RecordingBuilder& builder);

}  // namespace mbk
