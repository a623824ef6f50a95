#include "mb_kinematics/core/euler_order.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include "mb_kinematics/core/joint_motion.h"

namespace mbk {
namespace {

TEST(EulerOrderTest, TwelveOrdersRoundTripThroughTheirNames) {
  std::set<std::string> names;
  for (int i = 0; i <= static_cast<int>(EulerOrder::kLast); ++i) {
    const auto order = static_cast<EulerOrder>(i);
    const std::array<int, 3> a = euler_axes(order);
    EXPECT_NE(a[0], a[1]);
    EXPECT_NE(a[1], a[2]);
    EXPECT_EQ(euler_order_from_string(to_string(order)), order);
    EXPECT_EQ(euler_order_from_axes(a), order);
    EXPECT_EQ(is_tait_bryan(order), a[0] != a[2]);
    names.insert(to_string(order));
  }
  EXPECT_EQ(names.size(), 12u);
}

TEST(EulerOrderTest, DigitsAndLowerCaseAreRead) {
  EXPECT_EQ(euler_order_from_string("123"), EulerOrder::kXYZ);
  EXPECT_EQ(euler_order_from_string("313"), EulerOrder::kZXZ);
  EXPECT_EQ(euler_order_from_string("zxy"), EulerOrder::kZXY);
}

TEST(EulerOrderTest, BadOrdersAreRefusedByName) {
  for (const char* bad : {"XXY", "XY", "XYZW", "ABC", "112", ""}) {
    try {
      euler_order_from_string(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos);
    }
  }
  EXPECT_THROW(euler_order_from_axes({0, 0, 1}), std::invalid_argument);
}

// The three turns about the order's axes, by Eigen's angle-axis (independent of euler_map).
Mat3<double> turns(EulerOrder order, double alpha, double beta, double gamma) {
  const std::array<int, 3> a = euler_axes(order);
  return (Eigen::AngleAxisd(alpha, Vec3<double>::Unit(a[0])) *
          Eigen::AngleAxisd(beta, Vec3<double>::Unit(a[1])) *
          Eigen::AngleAxisd(gamma, Vec3<double>::Unit(a[2])))
      .toRotationMatrix();
}

// euler_order.h's identity R_a1 R_a2 R_a3 = P R_123(alpha, beta + shift, sign gamma) Q for every
// order, with P and Q proper signed permutations (and the 1-2-3 map the identity).
TEST(EulerOrderTest, EveryOrderIsThe123RotationBetweenTwoPermutations) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  for (int i = 0; i <= static_cast<int>(EulerOrder::kLast); ++i) {
    const auto order = static_cast<EulerOrder>(i);
    const EulerMap& map = euler_map(order);
    const Mat3<double> p = map.p.matrix(), q = map.q.matrix();
    EXPECT_NEAR(p.determinant(), 1.0, 0.0) << to_string(order);
    EXPECT_NEAR(q.determinant(), 1.0, 0.0) << to_string(order);
    EXPECT_EQ(map.shifted, !is_tait_bryan(order));
    for (int trial = 0; trial < 10; ++trial) {
      const double a = u(rng), b = u(rng), g = u(rng);
      const double shift = map.shifted ? M_PI / 2 : 0.0;
      const Mat3<double> r = p * rotation_123(a, b + shift, map.gamma_sign * g) * q;
      EXPECT_LT((r - turns(order, a, b, g)).norm(), 1e-14) << to_string(order);
    }
  }
  const EulerMap& xyz = euler_map(EulerOrder::kXYZ);
  EXPECT_TRUE(xyz.p.matrix().isIdentity() && xyz.q.matrix().isIdentity() && !xyz.shifted &&
              xyz.gamma_sign == 1);
}

// The kernels' view of each order (EulerTurns): its axes, the third axis and the sign sigma of
// e_a1 x e_a2 = sigma e_third, which the recursion's angle rates fold into sums and differences.
TEST(EulerOrderTest, TurnsNameEachOrdersAxesAndCrossProductSign) {
  for (int i = 0; i <= static_cast<int>(EulerOrder::kLast); ++i) {
    const auto order = static_cast<EulerOrder>(i);
    const EulerTurns o = euler_turns(order);
    const std::array<int, 3> a = euler_axes(order);
    EXPECT_EQ((std::array<int, 3>{o.a1, o.a2, o.a3}), a) << to_string(order);
    EXPECT_EQ(o.proper, !is_tait_bryan(order)) << to_string(order);
    EXPECT_NE(o.third, o.a1);
    EXPECT_NE(o.third, o.a2);
    const Vec3<double> cross = Vec3<double>::Unit(o.a1).cross(Vec3<double>::Unit(o.a2));
    EXPECT_EQ(cross, o.sigma * Vec3<double>::Unit(o.third)) << to_string(order);
  }
  const EulerTurns xyz = euler_turns(EulerOrder::kXYZ);
  EXPECT_TRUE(xyz.a1 == 0 && xyz.a2 == 1 && xyz.a3 == 2 && xyz.third == 2 && xyz.sigma == 1);
}

// joint_motion's rotation and joint_quaternion of a ball joint in each order are the three turns
// (C_k times them).
TEST(EulerOrderTest, JointMotionTurnsAboutTheOrdersAxes) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  for (int i = 0; i <= static_cast<int>(EulerOrder::kLast); ++i) {
    Joint joint;
    joint.type = JointType::kBall123;
    joint.euler_order = static_cast<EulerOrder>(i);
    joint.rotation = turns(EulerOrder::kZYX, u(rng), u(rng), u(rng));
    const double q[3] = {u(rng), u(rng), u(rng)};
    const Mat3<double> expected = joint.rotation * turns(joint.euler_order, q[0], q[1], q[2]);
    JointMotion<double> m;
    joint_motion<double>(joint, SpeedKind::kCoordinateDerivatives, q, nullptr, m);
    EXPECT_LT((m.rotation - expected).norm(), 1e-14) << to_string(joint.euler_order);
    const Eigen::Quaterniond offset(joint.rotation);
    EXPECT_LT((joint_quaternion<double>(joint, offset, q).toRotationMatrix() - expected).norm(),
              1e-14)
        << to_string(joint.euler_order);
  }
}

}  // namespace
}  // namespace mbk
