// The kinematics as a tidy CSV (mbk bag --csv): one row per sample and body, and one row per
// sample for the system's mass center (body "system", index 0) when the model has mass.
// Columns: stamp,body,index,lower_body, origin_x/y/z, qx,qy,qz,qw (S0K), mass_center_x/y/z,
// omega_x/y/z, alpha_x/y/z, velocity_x/y/z, acceleration_x/y/z (of the mass center); all in R.
// The system row leaves origin, orientation, omega and alpha empty. Numbers in their shortest
// round-trip form (io/number_format.h), the stamp with 9 decimals. Rows are formatted into a
// reused buffer and written a block at a time (io/block_file.h: a large file past the page
// cache): no allocation per row. A column more: its header name
// and one call in format(). With error bars (mbk bag's auto estimator), six columns more:
// alpha_se_x/y/z and acceleration_se_x/y/z, each R component's standard error (core/body_errors.h),
// empty where there are none (the system row; a row without them). TidyCsvExtras adds the segment
// frames and joint angles' columns after those (core/segment_frames.h, core/euler_angles.h), empty
// in the system row. ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/euler_angles.h"
#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/block_file.h"

namespace mbk {

// Columns beyond the default ones (mbk bag --body-axes, --angles; doc/recorded_data.md).
struct TidyCsvExtras {
  // omega_body_x/y/z, alpha_body_*, velocity_body_*, acceleration_body_*: in Bk's own axes.
  bool body_axes = false;
  // Per body k (index k; [0] unused), or empty for none: angle_order (e.g. ZXY), angle_1/2/3
  // (rad: Bk's rotation relative to L(k) in that order, continuous over the rows written),
  // relative_omega_x/y/z and relative_alpha_x/y/z (in L(k)'s axes).
  std::vector<EulerOrder> angles;
};

class TidyCsvWriter {
 public:
  // Throws std::invalid_argument if `path` cannot be written. `system` names the whole-body rows'
  // body ("system_incomplete" for a model that lacks segments of the body: load_model.h).
  TidyCsvWriter(const std::string& path, const Model& model, bool errors = false,
                const std::string& system = "system", const TidyCsvExtras& extras = {});
  TidyCsvWriter(const TidyCsvWriter&) = delete;
  TidyCsvWriter& operator=(const TidyCsvWriter&) = delete;

  static const char* header();
  static const char* errors_header();  // the error bars' columns, after header()'s
  // The extras' columns, after the error bars' (with a leading comma; "" for none).
  static std::string extras_header(const TidyCsvExtras& extras);
  // With angles the rows must be formatted in sample order by one thread (each sample's angles
  // continue the last one's): not by the computing threads.
  bool sequential() const { return !extras_.angles.empty(); }
  // With angles: the last row's (per body k, index k; [0] unused).
  const EulerAngleTrack& angles() const { return angles_; }
  // alpha_se, acceleration_se: per body, or nullptr (empty cells) when the writer has errors.
  void write(double stamp, const Data<double>& data,
             const std::vector<Vec3<double>>* alpha_se = nullptr,
             const std::vector<Vec3<double>>* acceleration_se = nullptr);
  // The rows of one sample appended to `text` (const: any thread may format while this one
  // writes; `text` keeps its capacity, so a reused string is not allocated again), and written.
  void format(double stamp, const Data<double>& data, std::string& text,
              const std::vector<Vec3<double>>* alpha_se = nullptr,
              const std::vector<Vec3<double>>* acceleration_se = nullptr) const;
  void write_text(const std::string& text);
  // The whole seconds the stamps given are counted from (Recording::origin); set before writing.
  void set_time_origin(double seconds) { origin_ = seconds; }
  // Writes what is left and closes; throws std::runtime_error if the disk refused the data.
  // Destroyed without close(), the rows still buffered are not written.
  void close() { file_.close(); }

 private:
  const Model& model_;
  BlockFile file_;
  double total_mass_ = 0;
  double origin_ = 0;
  bool errors_ = false;
  TidyCsvExtras extras_;
  mutable EulerAngleTrack angles_;       // per body, the joint angles (sequential())
  std::vector<std::string> body_cells_;  // per body k: ",name,k,L(k)"
  std::string system_cells_;             // ",system,0,0"
  std::string buffer_;                   // one sample's rows (write)
};

}  // namespace mbk
