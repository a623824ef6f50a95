#include "mb_kinematics/core/inertia.h"

#include <Eigen/Eigenvalues>
#include <sstream>

namespace mbk {

Mat3<double> inertia_matrix(double ixx, double iyy, double izz, double ixy, double ixz,
                            double iyz) {
  Mat3<double> i;
  i << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
  return i;
}

std::string inertia_problem(const Mat3<double>& inertia) {
  if (!inertia.allFinite()) return "is not finite";
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    return "is not symmetric";
  const Vec3<double> m = Eigen::SelfAdjointEigenSolver<Mat3<double>>(inertia).eigenvalues();
  const double tolerance = 1e-9 * std::abs(m.sum());
  std::ostringstream moments;
  moments.precision(6);
  moments << " (principal moments " << m[0] << ", " << m[1] << ", " << m[2] << ")";
  if (m[0] < -tolerance) return "is not positive semidefinite" + moments.str();
  if (m[0] + m[1] < m[2] - tolerance)  // m ascending: the one inequality that can fail
    return "violates the triangle inequality I1 + I2 >= I3" + moments.str();
  return "";
}

}  // namespace mbk
