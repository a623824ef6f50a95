// mbk bag --h5: the kinematics as an HDF5 file (libhdf5's C API), one dataset per quantity under
// the Python module's names and shapes (doc/recorded_data.md), N the rows written:
//   time (N,) s; rotation (N, B, 3, 3) S0K; origin, mass_center, omega, alpha, velocity,
//   acceleration (N, B, 3) (velocity, acceleration: of the mass center), all in R;
//   system_mass (N,), system_mass_center, system_velocity, system_acceleration, linear_momentum,
//   angular_momentum (N, 3) when the model has mass (NaN where Model.kinematics has NaN);
//   joint_position, joint_velocity, joint_acceleration (N, nq), the states computed from;
//   with error bars ("auto"): alpha_se, acceleration_se (N, B, 3), joint_velocity_se,
//   joint_acceleration_se (N, nq), NaN in a row without them;
//   body_names (B,), coordinate_names (nq,): UTF-8 strings.
// Each numeric dataset has a `unit` attribute; the file has `frame` (R), `model_file`, `input`,
// `estimator`, `system` ("system" or "system_incomplete": segments missing, as the CSV's rows)
// and `mbk_version`. Datasets are extendible, chunked by rows (about 1 MiB per chunk), written a
// chunk of rows at a time, optionally compressed (shuffle + deflate). Values are the doubles the
// CSV prints (its shortest round-trip text reads back to them). ROS-free.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace mbk_offline {

struct H5Attributes {
  std::string frame, model_file, input, estimator, system = "system";
};

class H5Output {
 public:
  // Creates `path` (the file to write now: OutputFile::writing()) for the bodies of `model` and
  // the coordinates `coordinates` (the joint states' model; with a floating base `model` has one
  // body more); `shown`: the path named in errors; errors: the *_se datasets; compression: the
  // deflate level, 0 (none) to 9. Throws std::invalid_argument if the file cannot be created.
  H5Output(const std::string& path, const std::string& shown, const mbk::Model& model,
           const std::vector<std::string>& coordinates, const H5Attributes& attributes, bool errors,
           int compression);
  ~H5Output();
  H5Output(const H5Output&) = delete;
  H5Output& operator=(const H5Output&) = delete;

  // Row `row` (its state and error bars) with the kinematics `data` (row.data, or carried into a
  // floating base's layout), buffered; a full chunk of rows is written.
  void write(const mbk::OfflineRow& row, const mbk::Data<double>& data);
  // The stamps' origin (Recording::origin, a trajectory CSV's wall-clock seconds): `time` holds
  // origin + stamp (io/number_format.h's written_stamp: the CSV's text of it, read back).
  void set_time_origin(double seconds);
  // Writes the rows left and closes the file; throws std::runtime_error ("PATH: write failed
  // (No space left on device)") if the file could not be written.
  void close();

 private:
  struct File;
  std::unique_ptr<File> file_;
};

}  // namespace mbk_offline
