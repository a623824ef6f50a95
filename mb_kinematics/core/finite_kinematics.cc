#include "mb_kinematics/core/finite_kinematics.h"

#include <Eigen/Core>

namespace mbk {
namespace {

// Every number of bodies 1..N in one of Data's arrays finite. x * 0 is 0 for a finite x and
// NaN for Inf or NaN, so one sum tells: the compiler vectorizes it without a branch per number.
template <typename M>
bool finite(const std::vector<M>& a) {
  constexpr int size = M::SizeAtCompileTime;
  static_assert(sizeof(M) == size * sizeof(double), "Data's arrays hold bare numbers");
  if (a.size() < 2) return true;
  const Eigen::Index n = size * (static_cast<Eigen::Index>(a.size()) - 1);
  return (Eigen::Map<const Eigen::ArrayXd>(a[1].data(), n) * 0.0).sum() == 0.0;
}

}  // namespace

bool finite_kinematics(const Data<double>& d, Level level) {
  bool ok = finite(d.rotation) && finite(d.origin) && finite(d.mass_center);
  if (level != Level::kPose)
    ok = ok && finite(d.omega) && finite(d.mass_center_velocity) && finite(d.origin_velocity);
  if (level == Level::kAcceleration)
    ok = ok && finite(d.alpha) && finite(d.mass_center_acceleration) &&
         finite(d.origin_acceleration);
  return ok;
}

bool finite_kinematics(const Data<double>& d, int k, Level level) {
  bool ok = d.rotation[k].allFinite() && d.origin[k].allFinite() && d.mass_center[k].allFinite();
  if (level != Level::kPose)
    ok = ok && d.omega[k].allFinite() && d.mass_center_velocity[k].allFinite() &&
         d.origin_velocity[k].allFinite();
  if (level == Level::kAcceleration)
    ok = ok && d.alpha[k].allFinite() && d.mass_center_acceleration[k].allFinite() &&
         d.origin_acceleration[k].allFinite();
  return ok;
}

}  // namespace mbk
