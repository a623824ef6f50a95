// mbk bag --mot: the joint angles (and with MotColumns::coordinates the joint coordinates) as an
// OpenSim Storage file (.mot), which OpenSim's Storage and STOFileAdapter read: a header (the
// table's name, version=1, nRows, nColumns, inDegrees=yes, endheader), the column labels, then
// one line per sample, all tab-separated. Columns: `time`; per body k = 1..N its three angles
// relative to its lower body (SJK = R_a1 R_a2 R_a3 in the body's order, doc/method.md 10; the
// angles the CSV's --angles columns hold, continuous from row to row), labelled
// `<body>_<axis>` (`hip_X`, `hip_Z`, `hip_Y` for XZY) or, for a proper Euler order whose first
// and third axes are one, `<body>_<axis><1|2|3>` (`shoulder_Y1`, `shoulder_X2`, `shoulder_Y3`);
// then, when asked, the coordinates under their names. A space or tab in a name becomes `_`
// (OpenSim splits labels at both). Angles in degrees (the joint angles; the coordinates of
// revolute joints and the angles of ball, free, planar and universal joints), translations in
// metres, Euler parameters as they are; the stamp as the CSV writes it, numbers in their shortest
// round-trip form (io/number_format.h). nRows is counted as the rows are written and set in the
// header at close(): the file must be seekable (a regular file, or /dev/null). ROS-free.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mb_kinematics/core/euler_angles.h"
#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/types.h"
#include "mb_kinematics/offline/offline_batch.h"

namespace mbk_offline {

// What the file holds besides `time`.
struct MotColumns {
  std::vector<mbk::EulerOrder> angles;  // per body k (index k; [0], R, unused): its angles' order
  bool coordinates = false;             // the joint coordinates after the angles
};

class MotOutput {
 public:
  // Creates `path` (the file to write now: OutputFile::writing()) for the joint angles of the
  // bodies of `bodies` and the coordinates of `model` (the same model, or `bodies` with a base
  // body added in front: offline/base_track.h); `shown`: the path named in errors. Throws
  // std::invalid_argument if it cannot, or if two columns would have one label.
  MotOutput(const std::string& path, const std::string& shown, const mbk::Model& model,
            const mbk::Model& bodies, const MotColumns& columns);
  ~MotOutput();
  MotOutput(const MotOutput&) = delete;
  MotOutput& operator=(const MotOutput&) = delete;

  // Row `row` (its stamp and coordinates), `data` its kinematics for `bodies`; rows in order
  // (each row's angles continue the row before's). `angles`: this row's, computed already in
  // the same orders (the CSV's --angles: TidyCsvWriter::angles()), or nullptr.
  void write(const mbk::OfflineRow& row, const mbk::Data<double>& data,
             const mbk::EulerAngleTrack* angles = nullptr);
  // The stamps' origin (Recording::origin): times written as the CSV writes them (whole seconds
  // and nanoseconds of origin + stamp).
  void set_time_origin(double seconds) { origin_ = seconds; }
  // Writes what is buffered, sets nRows and closes; throws std::runtime_error ("PATH: write
  // failed (...)") if the disk refused the data.
  void close();

  // The OpenSim column label of a coordinate name (spaces and tabs as `_`).
  static std::string label(const std::string& coordinate);
  // The labels of body `body`'s three angles in `order` (as above).
  static std::array<std::string, 3> angle_labels(const std::string& body, mbk::EulerOrder order);

 private:
  void flush();
  [[noreturn]] void fail(int error) const;
  std::string header(const mbk::Model& model, const mbk::Model& bodies) const;

  std::string shown_;
  int fd_ = -1;
  double origin_ = 0;
  const mbk::Model& bodies_;
  MotColumns columns_;
  mbk::EulerAngleTrack angles_;  // per body, when no angles are given to write()
  std::vector<double> scale_;    // per coordinate: 180 / pi for angles, else 1
  std::string buffer_;
  long rows_ = 0;
  int error_ = 0;  // the first write's errno
};

}  // namespace mbk_offline
