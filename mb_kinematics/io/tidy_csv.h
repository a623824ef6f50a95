// The kinematics as a tidy CSV (mbk bag --csv): one row per sample and body, and one row per
// sample for the system's mass center (body "system", index 0) when the model has mass.
// Columns: stamp,body,index,lower_body, origin_x/y/z, qx,qy,qz,qw (S0K), mass_center_x/y/z,
// omega_x/y/z, alpha_x/y/z, velocity_x/y/z, acceleration_x/y/z (of the mass center); all in R.
// The system row leaves origin, orientation, omega and alpha empty. ROS-free.
#pragma once

#include <cstdio>
#include <string>

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
  void number(double x);

  const Model& model_;
  std::string path_;
  std::FILE* file_ = nullptr;
  double total_mass_ = 0;
};

}  // namespace mbk
