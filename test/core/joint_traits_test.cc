// The joint traits table (mb_kinematics/core/joint.h) against what joint_motion computes, for
// every joint type: a new type whose table entry and motion disagree fails here.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/core/joint_motion.h"

namespace {

using mbk::CoordinateKind;
using mbk::JointType;
using mbk::SpeedKind;

TEST(JointTraits, EveryTypeHasADistinctNameThatReadsBack) {
  std::set<std::string> names;
  for (JointType type : mbk::all_joint_types()) {
    const std::string name = mbk::to_string(type);
    EXPECT_TRUE(names.insert(name).second) << name;
    EXPECT_EQ(mbk::joint_type_from_string(name), type) << name;
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(JointType::kLast) + 1);
  EXPECT_THROW(mbk::joint_type_from_string("hinge"), std::invalid_argument);
}

// kLast is the last type: a type appended after it (the compiler makes joint_traits handle it)
// without moving kLast would answer here instead of throwing, and be missing from
// all_joint_types().
TEST(JointTraits, NothingAfterTheLastType) {
  const int after = static_cast<int>(JointType::kLast) + 1;
  EXPECT_THROW(mbk::joint_traits(static_cast<JointType>(after)), std::invalid_argument);
}

// Every URDF joint type the reader knows maps to the type whose traits name it.
TEST(JointTraits, UrdfTypesReadBack) {
  for (JointType type : mbk::all_joint_types()) {
    const std::string urdf = mbk::joint_traits(type).urdf_type;
    if (urdf.empty()) continue;
    EXPECT_EQ(mbk::joint_type_from_urdf_type(urdf), type) << urdf;
  }
  EXPECT_EQ(mbk::joint_type_from_urdf_type("revolute"), JointType::kRevolute);
  EXPECT_THROW(mbk::joint_type_from_urdf_type("hinge"), std::invalid_argument);
}

TEST(JointTraits, TranslationsFirstAndEulerParametersLast) {
  for (JointType type : mbk::all_joint_types()) {
    SCOPED_TRACE(mbk::to_string(type));
    const int n = mbk::coordinate_count(type), t = mbk::translation_count(type);
    for (int i = 0; i < n; ++i)
      EXPECT_EQ(mbk::coordinate_kind(type, i) == CoordinateKind::kTranslation, i < t) << i;
    const int e = mbk::first_euler_parameter(type);
    EXPECT_EQ(mbk::uses_euler_parameters(type), e >= 0);
    if (e >= 0) {
      EXPECT_EQ(e + 4, n);
    }
    EXPECT_EQ(mbk::coordinate_suffixes(type).size(), static_cast<size_t>(n));
    for (SpeedKind speeds : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity})
      EXPECT_EQ(mbk::speed_suffixes(type, speeds).size(),
                static_cast<size_t>(mbk::speed_count(type, speeds)));
  }
}

// joint_motion's speed layout (linear speeds first, then rotation rates) is the table's.
TEST(JointTraits, MatchJointMotion) {
  for (JointType type : mbk::all_joint_types()) {
    for (SpeedKind speeds : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity}) {
      SCOPED_TRACE(mbk::to_string(type));
      mbk::Joint joint;
      joint.type = type;
      std::vector<double> q(mbk::coordinate_count(type), 0.3), qd(mbk::kMaxJointSpeeds, 0.1);
      if (mbk::uses_euler_parameters(type)) q.back() = 1.0;
      mbk::JointMotion<double> m;
      mbk::joint_motion<double>(joint, speeds, q.data(), qd.data(), m);
      EXPECT_EQ(m.speeds, mbk::speed_count(type, speeds));
      EXPECT_EQ(m.linear_speeds, mbk::translation_count(type));
      EXPECT_EQ(m.translation.isZero(), mbk::translation_count(type) == 0);
      EXPECT_EQ(m.rotation.isIdentity(), m.speeds == m.linear_speeds);
    }
  }
}

// joint_quaternion (the tf output's SJK) is joint_motion's rotation, for every type, with and
// without an offset rotation C_k, at random coordinates (Euler parameters not normalized).
TEST(JointQuaternion, IsJointMotionsRotation) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const Eigen::Matrix3d tilted =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  for (JointType type : mbk::all_joint_types()) {
    for (const Eigen::Matrix3d& c : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), tilted}) {
      SCOPED_TRACE(mbk::to_string(type));
      mbk::Joint joint;
      joint.type = type;
      joint.axis = Eigen::Vector3d(0.3, -0.4, 0.2).normalized();
      joint.rotation = c;
      for (int trial = 0; trial < 20; ++trial) {
        std::vector<double> q(mbk::coordinate_count(type));
        for (double& x : q) x = u(rng);
        mbk::JointMotion<double> m;
        mbk::joint_motion<double>(joint, SpeedKind::kCoordinateDerivatives, q.data(), nullptr, m);
        const Eigen::Quaterniond r = mbk::joint_quaternion(joint, Eigen::Quaterniond(c), q.data());
        EXPECT_NEAR(r.norm(), 1.0, 1e-15);
        // Within rounding: each side multiplies a few rotations (5.5 eps at most seen here).
        EXPECT_LT((r.toRotationMatrix() - m.rotation).cwiseAbs().maxCoeff(), 16 * kEps);
      }
    }
  }
}

}  // namespace
