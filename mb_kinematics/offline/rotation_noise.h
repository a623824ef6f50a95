// The noise of the rotations that ball and free joints on angles record (doc/method.md 11): each
// sample's residuals r_i of the angles from "auto"'s shortest fit, turned into the small rotation
// E(q_i) r_i of SJK (core/rotation_errors.h), and their covariance (Bj axes)
//   Sigma = sum_i E(q_i) r_i r_i^T E(q_i)^T / (n - tr H)
// (tr H: the fits' weights on their own samples, as the coordinates' noise levels of
// estimation/auto_estimator.h). Near gimbal lock the angles' residuals are large and correlated
// and their rotations are not. Summed a piece of the recording at a time (offline/offline_stream.h)
// or whole, in the same order: the same bits.
#pragma once

#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/offline_estimator.h"

namespace mbk {

// A joint on angles (takes_euler_order) whose rotation's error bars are carried as a rotation:
// its body and its first angle coordinate (the three follow). Mimic coordinates are left out.
struct AngleJoint {
  int body = 0, coordinate = 0;
};
std::vector<AngleJoint> angle_joints(const Model& model);
// `choice` with the accelerations of the angles of `joints` from "auto"'s first chain alone
// (AutoChoice::centred_choice -1): their error bars are carried on the rotation, and an angle's
// own noise level, near gimbal lock far above the rotation's, says nothing of the bias the
// centred chain's steps show (its error bars would cover 46 % of the spine's alpha errors of
// test/offline/gimbal_lock_errors_test.cc).
AutoChoice angles_first_chain(AutoChoice choice, const std::vector<AngleJoint>& joints);

class RotationNoise {
 public:
  // dt: the recording's median interval ("auto"'s candidates').
  RotationNoise(const Model& model, double dt);
  // Rows [from, to) of a piece of the recording (stamps t, their segments, positions
  // x[r * ld + c]), each row's shortest window lying in the piece as in the recording. In order.
  void add(const std::vector<double>& t, const Segments& segments, const double* x, int ld,
           int from, int to);
  const std::vector<AngleJoint>& joints() const { return joints_; }
  // Per joint of joints(): Sigma (0 with fewer samples than the fits' trace).
  std::vector<Mat3<double>> covariance() const;

 private:
  const Model& model_;
  std::vector<AngleJoint> joints_;
  OfflineEstimator shortest_;
  DerivativeWeights w_;
  std::vector<Mat3<double>> sum_;
  double trace_ = 0, count_ = 0;
};

}  // namespace mbk
