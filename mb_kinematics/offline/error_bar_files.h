// The CSV's side files of error bars ("auto", doc/recorded_data.md): OUT.errors.csv, a row per
// coordinate, and OUT.sample_errors.csv, a row per sample; each written under a temporary name
// and renamed when whole (output_file.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/block_file.h"
#include "mb_kinematics/offline/offline_kinematics.h"
#include "mb_kinematics/offline/output_file.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk_offline {

// The error bars' side files go beside a CSV that is (or will be) a regular file only: not
// beside /dev/null, /dev/stdout or a pipe (which would put /dev/null.errors.csv into /dev).
bool has_side_files(const std::string& csv);

// OUT.csv's side file of error bars: OUT.errors.csv (or OUT`suffix`).
std::string errors_path(const std::string& csv, const char* suffix = ".errors.csv");

// OUT.csv's side file of each sample's error bars, OUT.sample_errors.csv ("auto", every
// coordinate in every sample): stamp, then <coordinate>_velocity_se, <coordinate>_acceleration_se
// per coordinate (0 where the sample gives it or a mimic rule sets it), a row per sample read,
// each number to 6 significant digits (%g); written a piece at a time as the CSV is (formatted
// into one reused buffer, io/block_file.h), under a temporary name until commit().
class SampleErrorsFile {
 public:
  SampleErrorsFile(std::string path, const mbk::Model& model);
  // Rows [begin, end) of `rec`; nothing without error bars (states.coordinate_errors).
  void write(const mbk::Recording& rec, const mbk::OfflineStates& states, int begin, int end);
  void commit();

 private:
  void open();
  std::string path_;
  const mbk::Model& model_;
  std::vector<double> v_, a_;
  std::unique_ptr<OutputFile> file_;
  std::unique_ptr<mbk::BlockFile> block_;
  std::vector<char> row_;  // one row's text
};

// OUT.errors.csv: one row per coordinate, coordinate,noise,velocity_se,acceleration_se (medians
// over samples, to a relative 2^-11: MedianHistogram).
void write_errors(const std::string& path, const std::vector<mbk::CoordinateError>& errors);

}  // namespace mbk_offline
