// mbk bag --mot: the joint coordinates as an OpenSim Storage file (.mot), which OpenSim's
// Storage and STOFileAdapter read: a header (the table's name, version=1, nRows, nColumns,
// inDegrees=yes, endheader), the column labels `time` and the coordinate names (a space or
// tab in a name becomes `_`: OpenSim splits labels at both), then one line per sample, all
// tab-separated. Angles in degrees (the model's revolute, ball and free joints' angles),
// translations in metres, Euler parameters as they are; the stamp as the CSV writes it, numbers in
// their shortest round-trip form (io/number_format.h). nRows is counted as the rows are written and set in the header at
// close(): the file must be seekable (a regular file, or /dev/null). ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace mbk_offline {

class MotOutput {
 public:
  // Creates `path` (the file to write now: OutputFile::writing()) for the coordinates of
  // `model`; `shown`: the path named in errors. Throws std::invalid_argument if it cannot.
  MotOutput(const std::string& path, const std::string& shown, const mbk::Model& model);
  ~MotOutput();
  MotOutput(const MotOutput&) = delete;
  MotOutput& operator=(const MotOutput&) = delete;

  void write(const mbk::OfflineRow& row);  // its stamp and coordinates
  // The stamps' origin (Recording::origin): the times are origin + stamp (written as the CSV
  // writes them, whole seconds and nanoseconds).
  void set_time_origin(double seconds) { origin_ = seconds; }
  // Writes what is buffered, sets nRows and closes; throws std::runtime_error ("PATH: write
  // failed (...)") if the disk refused the data.
  void close();

  // The OpenSim column label of a coordinate name (spaces and tabs as `_`).
  static std::string label(const std::string& coordinate);

 private:
  void flush();
  [[noreturn]] void fail(int error) const;

  std::string shown_;
  int fd_ = -1;
  double origin_ = 0;
  std::vector<double> scale_;  // per coordinate: 180 / pi for angles, else 1
  std::string buffer_;
  long rows_ = 0;
  off_t rows_at_ = 0;  // where nRows' digits go
  int error_ = 0;      // the first write's errno
};

}  // namespace mbk_offline
