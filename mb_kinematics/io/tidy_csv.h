// The kinematics as a tidy CSV (mbk bag --csv): one row per sample and body, and one row per
// sample for the system's mass center (body "system", index 0) when the model has mass.
// Columns: stamp,body,index,lower_body, origin_x/y/z, qx,qy,qz,qw (S0K), mass_center_x/y/z,
// omega_x/y/z, alpha_x/y/z, velocity_x/y/z, acceleration_x/y/z (of the mass center); all in R.
// The system row leaves origin, orientation, omega and alpha empty. Numbers in their shortest
// round-trip form (io/number_format.h), the stamp with 9 decimals. Rows are formatted into a
// buffer written out a block at a time: no allocation per row. ROS-free.
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
  // Flushes and closes; throws if the disk refused the data.
  void close();

 private:
  // Cells are appended to buffer_; each call makes room for itself (a new column is one call).
  void number(double x);               // ",x"
  void text(const char* s, size_t n);  // s as it is
  void text(const std::string& s) { text(s.data(), s.size()); }
  void end_row() { text("\n", 1); }
  void flush();

  const Model& model_;
  std::string path_;
  std::FILE* file_ = nullptr;
  double total_mass_ = 0;
  std::vector<std::string> body_cells_;  // per body k: ",name,k,L(k)"
  std::vector<char> buffer_;
  size_t used_ = 0;
};

}  // namespace mbk
