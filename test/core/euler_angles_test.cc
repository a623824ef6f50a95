// Cardan/Euler angles of rotations (core/euler_angles.h) in all 12 orders: the round trip to the
// rotation, the principal ranges, the joint coordinates of ball joints back from their relative
// rotation, gimbal-adjacent rotations, and series kept continuous across +-pi and through a
// gimbal lock.
#include "mb_kinematics/core/euler_angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/segment_frames.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;
using mbk::EulerOrder;

// A rotation and its angles are a few (< 40) rounded operations on O(1) numbers: 1e-14 on the
// matrix (Frobenius norm) leaves ~4x margin over the ulps (measured worst 2.1e-15 on 240,000
// random rotations, 2.7e-15 at 0 to 1e-4 from gimbal lock).
constexpr double kTol = 1e-14;

std::vector<EulerOrder> all_orders() {
  std::vector<EulerOrder> out;
  for (int i = 0; i <= static_cast<int>(EulerOrder::kLast); ++i)
    out.push_back(static_cast<EulerOrder>(i));
  return out;
}

M random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// The order's beta at gimbal lock: +-pi/2 (Tait-Bryan), pi or 0 (proper Euler).
double lock_beta(EulerOrder order, int side) {
  if (mbk::is_tait_bryan(order)) return side * M_PI / 2;
  return side > 0 ? M_PI : 0.0;
}

TEST(EulerAngles, RoundTripAndPrincipalRangesInEveryOrder) {
  std::mt19937 rng(3);
  for (EulerOrder order : all_orders()) {
    const std::string name = mbk::to_string(order);
    for (int n = 0; n < 200; ++n) {
      const M r = random_rotation(rng);
      const V x = mbk::euler_angles(r, order);
      EXPECT_LE((mbk::rotation_from_euler_angles(x, order) - r).norm(), kTol) << name;
      EXPECT_LE(std::abs(x[0]), M_PI) << name;
      EXPECT_LE(std::abs(x[2]), M_PI) << name;
      if (mbk::is_tait_bryan(order)) {
        EXPECT_LE(std::abs(x[1]), M_PI / 2) << name;
      } else {
        EXPECT_GE(x[1], 0.0) << name;
        EXPECT_LE(x[1], M_PI) << name;
      }
    }
  }
}

// Angles drawn inside the principal ranges come back (the set is unique away from gimbal lock).
TEST(EulerAngles, PrincipalAnglesComeBack) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.99, 0.99);
  for (EulerOrder order : all_orders()) {
    for (int n = 0; n < 100; ++n) {
      const double b = mbk::is_tait_bryan(order) ? u(rng) * M_PI / 2 : (u(rng) + 1) * M_PI / 2;
      const V x(u(rng) * M_PI, b, u(rng) * M_PI);
      const V y = mbk::euler_angles(mbk::rotation_from_euler_angles(x, order), order);
      EXPECT_LE((y - x).norm(),
                1e-12 / std::abs(std::cos(b - (mbk::is_tait_bryan(order) ? 0.0 : M_PI / 2))))
          << mbk::to_string(order) << " " << x.transpose() << " -> " << y.transpose();
    }
  }
}

// A ball joint in each order (C_k = I on a moving lower body): the angles of relative_rotation
// are its coordinates.
TEST(EulerAngles, BallJointCoordinatesFromTheRelativeRotation) {
  for (EulerOrder order : all_orders()) {
    mbk::Model model;
    model.bodies.resize(3);
    for (int k = 1; k <= 2; ++k) {
      mbk::Body& b = model.bodies[k];
      b.name = "b" + std::to_string(k);
      b.lower = k - 1;
      b.joint.name = "j" + std::to_string(k);
      b.joint.type = mbk::JointType::kBall123;
      b.joint.euler_order = order;
      b.joint.offset = V(0.1, 0.2 * k, 0.3);
    }
    mbk::finalize_model(model);
    mbk::JointState<double> s(model);
    const double beta = mbk::is_tait_bryan(order) ? 0.4 : 1.2;
    s.position << 0.3, 0.2, -0.5, -2.5, beta, 2.9;
    mbk::Data<double> d(model);
    mbk::forward_kinematics(model, s, d, mbk::Level::kPose);
    const V x = mbk::euler_angles(mbk::relative_motion(model, d, 2).rotation, order);
    EXPECT_LE((x - V(-2.5, beta, 2.9)).norm(), 1e-13) << mbk::to_string(order);
  }
}

// Near and at gimbal lock: the angles still give the rotation back; at the lock the first angle
// is 0 (principal) or the previous sample's (near).
TEST(EulerAngles, GimbalAdjacentRotations) {
  for (EulerOrder order : all_orders()) {
    for (int side : {-1, 1}) {
      for (double off : {1e-4, 1e-7, 1e-9, 1e-12, 1e-15, 0.0}) {
        const double b = lock_beta(order, side) - side * off;  // toward the inside of the range
        const V x(0.7, b, -1.9);
        const M r = mbk::rotation_from_euler_angles(x, order);
        const std::string what = mbk::to_string(order) + " off " + std::to_string(off);
        const V y = mbk::euler_angles(r, order);
        EXPECT_LE((mbk::rotation_from_euler_angles(y, order) - r).norm(), kTol) << what;
        const V z = mbk::euler_angles_near(r, order, V(0.69, b, -1.89));
        EXPECT_LE((mbk::rotation_from_euler_angles(z, order) - r).norm(), kTol) << what;
        if (off == 0.0) {
          EXPECT_EQ(y[0], 0.0) << what;
          EXPECT_EQ(z[0], 0.69) << what;
        } else if (off >= 1e-7) {
          EXPECT_LE((z - x).norm(), 1e-6) << what;  // defined: the same set as x
        }
      }
    }
  }
}

// Samples whose angles run across +-pi, and through the gimbal lock (Tait-Bryan beta from 70 to
// 110 degrees, proper Euler from 20 to -20): no jump between samples, every sample round trips,
// and the angles follow the truth's family (alpha ends past pi, 0.4 from where it began).
TEST(EulerAngles, SeriesAreContinuous) {
  const int n = 201;
  for (EulerOrder order : all_orders()) {
    const bool tb = mbk::is_tait_bryan(order);
    const double b0 = tb ? M_PI / 2 : 0.0, sweep = tb ? 0.35 : -0.35;
    std::vector<double> rotations(9 * n), angles(3 * n);
    std::vector<V> truth(n);
    for (int i = 0; i < n; ++i) {
      const double t = i / double(n - 1);  // 0..1
      truth[i] = V(3.0 + 0.4 * t, b0 + sweep * (t - 0.5) * 2, -3.0 - 0.5 * t);
      const M r = mbk::rotation_from_euler_angles(truth[i], order);
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rotations.data() + 9 * i) = r;
    }
    mbk::euler_angle_series(rotations.data(), n, 1, {order}, angles.data());
    for (int i = 1; i < n; ++i) {
      const V a(angles.data() + 3 * i), p(angles.data() + 3 * (i - 1));
      EXPECT_LE((a - p).cwiseAbs().maxCoeff(), 0.02) << mbk::to_string(order) << " sample " << i;
      EXPECT_LE((mbk::rotation_from_euler_angles(a, order) -
                 mbk::rotation_from_euler_angles(truth[i], order))
                    .norm(),
                kTol)
          << mbk::to_string(order) << " sample " << i;
    }
    const V first(angles.data()), last(angles.data() + 3 * (n - 1));
    EXPECT_LE((first - truth[0]).norm(), 1e-12) << mbk::to_string(order);
    EXPECT_LE((last - truth[n - 1]).norm(), 1e-9) << mbk::to_string(order);
    EXPECT_GT(last[0], M_PI) << mbk::to_string(order);
  }
}

TEST(EulerAngles, OneOrderPerSeries) {
  std::mt19937 rng(9);
  const M r1 = random_rotation(rng), r2 = random_rotation(rng);
  std::vector<double> rotations(18), angles(6);
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rotations.data()) = r1;
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rotations.data() + 9) = r2;
  mbk::euler_angle_series(rotations.data(), 1, 2, {EulerOrder::kZXY, EulerOrder::kYZY},
                          angles.data());
  EXPECT_EQ(V(angles.data()), mbk::euler_angles(r1, EulerOrder::kZXY));
  EXPECT_EQ(V(angles.data() + 3), mbk::euler_angles(r2, EulerOrder::kYZY));
  EXPECT_THROW(mbk::euler_angle_series(rotations.data(), 1, 2,
                                       {EulerOrder::kZXY, EulerOrder::kXYZ, EulerOrder::kXYZ},
                                       angles.data()),
               std::invalid_argument);
}

// EulerAngleTrack (mbk bag's --angles and --mot): each series continues its own last angles, its
// first rotation principal, whenever it comes.
TEST(EulerAngles, TrackContinuesEachSeriesOnItsOwn) {
  const M turn_far = (Eigen::AngleAxisd(3.0, V::UnitZ())).toRotationMatrix();
  const M turn_past = (Eigen::AngleAxisd(3.3, V::UnitZ())).toRotationMatrix();  // past pi
  mbk::EulerAngleTrack track({EulerOrder::kXYZ, EulerOrder::kZXY});
  EXPECT_EQ(track.next(0, turn_far), mbk::euler_angles(turn_far, EulerOrder::kXYZ));
  const V continued = track.next(0, turn_past);
  EXPECT_NEAR(continued[2], 3.3, 1e-12);  // not 3.3 - 2 pi
  EXPECT_EQ(track.last(0), continued);
  // series 1 starts now, at the rotation series 0 continued through: principal, in ZXY
  EXPECT_EQ(track.next(1, turn_past), mbk::euler_angles(turn_past, EulerOrder::kZXY));
  EXPECT_NEAR(track.last(1)[0], 3.3 - 2 * M_PI, 1e-12);
  EXPECT_EQ(track.order(1), EulerOrder::kZXY);
}

}  // namespace
