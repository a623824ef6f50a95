// The kinematics as a tidy CSV (mbk bag --csv): one row per sample and body, and one row per
// sample for the system's mass center (body "system", index 0) when the model has mass.
// Columns: stamp,body,index,lower_body, origin_x/y/z, qx,qy,qz,qw (S0K), mass_center_x/y/z,
// omega_x/y/z, alpha_x/y/z, velocity_x/y/z, acceleration_x/y/z (of the mass center); all in R.
// The system row leaves origin, orientation, omega and alpha empty. Numbers in their shortest
// round-trip form (io/number_format.h), the stamp with 9 decimals. Rows are formatted into a
// buffer written out a block at a time: no allocation per row. A column more: its header name
// and one call in format(). ROS-free.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"

namespace mbk {

class TidyCsvWriter {
 public:
  // Throws std::invalid_argument if `path` cannot be written.
  TidyCsvWriter(const std::string& path, const Model& model);
  ~TidyCsvWriter();
  TidyCsvWriter(const TidyCsvWriter&) = delete;
  TidyCsvWriter& operator=(const TidyCsvWriter&) = delete;

  static const char* header();
  void write(double stamp, const Data<double>& data);
  // The rows of one sample appended to `text` (const: any thread may format while this one
  // writes; `text` keeps its capacity, so a reused string is not allocated again), and written.
  void format(double stamp, const Data<double>& data, std::string& text) const;
  void write_text(const std::string& text);
  // Flushes and closes; throws if the disk refused the data.
  void close();

 private:
  void flush();

  const Model& model_;
  std::string path_;
  std::FILE* file_ = nullptr;
  double total_mass_ = 0;
  std::vector<std::string> body_cells_;  // per body k: ",name,k,L(k)"
  std::string buffer_;                   // rows not yet written
};

}  // namespace mbk
