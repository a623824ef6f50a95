#include "mb_kinematics/core/euler_angles.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace mbk {
namespace {

// At or below this cos(beta') the first angle is taken as given (gimbal lock): a rotation's
// elements there are rounding noise, and a first angle off by d changes the rotation by about
// cos(beta') d, below 1e-14 for any d. Above it atan2 sets the first angle (to about 1e-16 /
// cos(beta') rad) and the third makes up the rest exactly.
constexpr double kLock = 1e-15;

// Elementary turn about axis i (0 = x, 1 = y, 2 = z).
Mat3<double> turn(int axis, double angle) {
  return Eigen::AngleAxisd(angle, Vec3<double>::Unit(axis)).toRotationMatrix();
}

// The 1-2-3 angles (a, b, g) of m = A(a) B(b) C(g) (eq. 4.4.9-4.4.12) with b in [-pi/2, pi/2]:
// a from m's last column, else `a_lock` at gimbal lock; g then from C = (A B)^T m, so that the
// three give m back to rounding even near the lock, where a alone is poorly defined.
Vec3<double> angles_123(const Mat3<double>& m, double a_lock) {
  const double cb = std::hypot(m(1, 2), m(2, 2));
  const double b = std::atan2(m(0, 2), cb);
  const double a = cb > kLock ? std::atan2(-m(1, 2), m(2, 2)) : a_lock;
  const Mat3<double> c = (turn(0, a) * turn(1, b)).transpose() * m;
  return Vec3<double>(a, b, std::atan2(c(1, 0), c(0, 0)));
}

// The angles in `order` from P^T r Q^T's 1-2-3 angles (euler_order.h): beta = beta' - shift,
// gamma = sign gamma'.
Vec3<double> raw_angles(const Mat3<double>& r, EulerOrder order, double alpha_lock) {
  const EulerMap& map = euler_map(order);
  Vec3<double> x =
      angles_123(map.p.matrix().transpose() * r * map.q.matrix().transpose(), alpha_lock);
  if (map.shifted) x[1] -= M_PI / 2;
  x[2] *= map.gamma_sign;
  return x;
}

// The other set of angles of the same rotation.
Vec3<double> other_set(const Vec3<double>& x, EulerOrder order) {
  return Vec3<double>(x[0] + M_PI, (is_tait_bryan(order) ? M_PI : 0.0) - x[1], x[2] + M_PI);
}

// x + 2 pi n, n the integer that brings it nearest `to`.
double nearest_turn(double x, double to) {
  return x + 2 * M_PI * std::round((to - x) / (2 * M_PI));
}

Vec3<double> nearest_turns(const Vec3<double>& x, const Vec3<double>& to) {
  return Vec3<double>(nearest_turn(x[0], to[0]), nearest_turn(x[1], to[1]),
                      nearest_turn(x[2], to[2]));
}

}  // namespace

Vec3<double> euler_angles(const Mat3<double>& r, EulerOrder order) {
  if (is_tait_bryan(order)) return raw_angles(r, order, 0.0);
  // Proper Euler: beta' - pi/2 is in [-pi, 0]; the other set has beta in [0, pi] (and, at gimbal
  // lock, alpha = -pi + pi = 0).
  const Vec3<double> x = raw_angles(r, order, -M_PI);
  const Vec3<double> y = other_set(x, order);
  return Vec3<double>(std::remainder(y[0], 2 * M_PI), y[1], std::remainder(y[2], 2 * M_PI));
}

Vec3<double> euler_angles_near(const Mat3<double>& r, EulerOrder order,
                               const Vec3<double>& previous) {
  const Vec3<double> x = nearest_turns(raw_angles(r, order, previous[0]), previous);
  const Vec3<double> y = nearest_turns(other_set(x, order), previous);
  return (y - previous).squaredNorm() < (x - previous).squaredNorm() ? y : x;
}

EulerAngleTrack::EulerAngleTrack(std::vector<EulerOrder> orders)
    : orders_(std::move(orders)),
      angles_(orders_.size(), Vec3<double>::Zero()),
      started_(orders_.size(), 0) {}

const Vec3<double>& EulerAngleTrack::next(std::size_t s, const Mat3<double>& r) {
  angles_[s] =
      started_[s] ? euler_angles_near(r, orders_[s], angles_[s]) : euler_angles(r, orders_[s]);
  started_[s] = 1;
  return angles_[s];
}

void euler_angle_series(const double* rotations, std::size_t samples, std::size_t series,
                        const std::vector<EulerOrder>& orders, double* angles) {
  if (orders.size() != 1 && orders.size() != series)
    throw std::invalid_argument("euler_angle_series: " + std::to_string(orders.size()) +
                                " orders for " + std::to_string(series) + " series");
  EulerAngleTrack track(orders.size() == 1 ? std::vector<EulerOrder>(series, orders[0]) : orders);
  for (std::size_t at = 0; at < samples * series; ++at)
    Eigen::Map<Vec3<double>>(angles + 3 * at) = track.next(
        at % series,
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rotations + 9 * at));
}

Mat3<double> rotation_from_euler_angles(const Vec3<double>& angles, EulerOrder order) {
  const EulerTurns t = euler_turns(order);
  return turn(t.a1, angles[0]) * turn(t.a2, angles[1]) * turn(t.a3, angles[2]);
}

}  // namespace mbk
