#include "mb_kinematics/core/floating_base.h"

#include <algorithm>

#include "mb_kinematics/core/point_kinematics.h"

namespace mbk {

bool interpolate_base(const std::vector<BaseSample>& samples,
                      const std::vector<Vec3<double>>& linear_acceleration,
                      const std::vector<Vec3<double>>& angular_acceleration, double t,
                      BaseMotion& out) {
  if (samples.empty() || t < samples.front().t || t > samples.back().t) return false;
  const auto after = std::lower_bound(samples.begin(), samples.end(), t,
                                      [](const BaseSample& s, double x) { return s.t < x; });
  const size_t j = after - samples.begin(), i = j == 0 ? 0 : j - 1;
  const BaseSample &a = samples[i], &b = samples[j];
  const double u = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
  const Eigen::Quaterniond q = a.orientation.slerp(u, b.orientation);
  out.rotation = q.toRotationMatrix();
  out.position = (1 - u) * a.position + u * b.position;
  out.velocity = (1 - u) * (a.orientation * a.linear) + u * (b.orientation * b.linear);
  out.omega = (1 - u) * (a.orientation * a.angular) + u * (b.orientation * b.angular);
  out.acceleration = (1 - u) * linear_acceleration[i] + u * linear_acceleration[j];
  out.alpha = (1 - u) * angular_acceleration[i] + u * angular_acceleration[j];
  return true;
}

void extrapolate_base(const BaseSample& s, const Vec3<double>& linear_acceleration,
                      const Vec3<double>& angular_acceleration, double dt, BaseMotion& out) {
  const Vec3<double> w = s.orientation * s.angular, v = s.orientation * s.linear;  // in R
  const double angle = w.norm() * dt;
  const Eigen::Quaterniond turn =
      angle == 0 ? Eigen::Quaterniond::Identity()
                 : Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized()));
  out.rotation = (turn * s.orientation).toRotationMatrix();
  out.position = s.position + dt * v;
  out.velocity = v;
  out.omega = w;
  out.acceleration = linear_acceleration;
  out.alpha = angular_acceleration;
}

void apply_floating_base(const BaseMotion& base, Data<double>& data) {
  const Mat3<double>& rb = base.rotation;
  const Vec3<double>& w = base.omega;
  const PointMotion<Vec3<double>> origin{base.position, base.velocity, base.acceleration};
  const auto carry = [&](Vec3<double>& p, Vec3<double>& v, Vec3<double>& a) {
    const Vec3<double> r = rb * p, vr = rb * v;  // relative position and velocity, in R
    const PointMotion<Vec3<double>> fixed = fixed_point(origin, w, base.alpha, r);  // r fixed
    a = fixed.acceleration + 2 * w.cross(vr) + rb * a;  // and moving: Coriolis, relative
    v = fixed.velocity + vr;
    p = fixed.position;
  };
  data.rotation[0] = rb;  // the root frame, where the root link's mass center sits
  data.origin[0] = base.position;
  data.origin_velocity[0] = base.velocity;
  data.origin_acceleration[0] = base.acceleration;
  data.omega[0] = w;
  data.alpha[0] = base.alpha;
  for (size_t k = 1; k < data.rotation.size(); ++k) {
    data.rotation[k] = rb * data.rotation[k];
    const Vec3<double> omega = rb * data.omega[k];
    data.alpha[k] = base.alpha + w.cross(omega) + rb * data.alpha[k];
    data.omega[k] = w + omega;
    carry(data.mass_center[k], data.mass_center_velocity[k], data.mass_center_acceleration[k]);
    carry(data.origin[k], data.origin_velocity[k], data.origin_acceleration[k]);
  }
}

}  // namespace mbk
