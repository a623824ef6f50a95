// point_velocity / point_acceleration (core/body_velocity.h): against central differences of
// the point's own position and velocity along smooth trajectories on random trees, at O_k and
// G_k against forward_kinematics, and in Bk's components against a closed form.
#include "mb_kinematics/core/body_velocity.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using mbk::ReferenceFrame;

// Central differences with h = 5e-4: error ~1e-11 relative to the largest of |f|, |f'| (see
// finite_difference_test.cc for the derivation); a wrong term is O(|f'|).
constexpr double kH = 5e-4;
constexpr double kFdTol = 1e-10;
constexpr double kTol = 1e-13;  // the same formula evaluated twice: rounding only

// A point of Bk at r from O_k, in Bk (not the mass center).
V point(int k) { return V(0.3 - 0.1 * k, 0.2, -0.4 + 0.05 * k); }

TEST(BodyVelocity, IsTheTimeDerivativeOfThePointsPositionAndVelocity) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const mbk::Model model = mbk_test::random_tree(12, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    const double t = 0.7;
    std::vector<mbk::Data<double>> samples;
    for (double offset : mbk_test::kStencilOffsets) {
      samples.emplace_back(model);
      mbk::forward_kinematics(model, trajectory.at<double>(t + offset * kH), samples.back());
    }
    mbk::Data<double> data(model);
    mbk::forward_kinematics(model, trajectory.at<double>(t), data);
    for (int k = 1; k <= model.body_count(); ++k) {
      const V r = point(k);
      const V p_dot = mbk_test::central_difference<V>(
          [&](int i) -> V { return samples[i].origin[k] + samples[i].rotation[k] * r; }, kH);
      const V v_dot = mbk_test::central_difference<V>(
          [&](int i) -> V {
            return mbk::point_velocity(samples[i], k, r, ReferenceFrame::kInertial).linear;
          },
          kH);
      const auto v = mbk::point_velocity(data, k, r, ReferenceFrame::kInertial);
      const auto a = mbk::point_acceleration(data, k, r, ReferenceFrame::kInertial);
      const std::string where = "seed " + std::to_string(seed) + " body " + std::to_string(k);
      EXPECT_LT((v.linear - p_dot).norm(), kFdTol * std::max({1.0, p_dot.norm()})) << where;
      EXPECT_LT((a.linear - v_dot).norm(), kFdTol * std::max({1.0, v.linear.norm(), v_dot.norm()}))
          << where;
      EXPECT_EQ(v.angular, data.omega[k]) << where;
      EXPECT_EQ(a.angular, data.alpha[k]) << where;
    }
  }
}

// r = 0 is O_k, r = r_k is G_k: the recursion's own values.
TEST(BodyVelocity, AtOriginAndMassCenterMatchesForwardKinematics) {
  const mbk::Model model = mbk_test::random_tree(20, 5);
  const mbk_test::Trajectory trajectory(model, 5);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, trajectory.at<double>(1.3), data);
  for (int k = 1; k <= model.body_count(); ++k) {
    const V zero = V::Zero(), r_k = model.bodies[k].mass_center;
    const double scale =
        1 + data.mass_center_velocity[k].norm() + data.mass_center_acceleration[k].norm();
    EXPECT_EQ(mbk::point_velocity(data, k, zero, ReferenceFrame::kInertial).linear,
              data.origin_velocity[k]);
    EXPECT_EQ(mbk::point_acceleration(data, k, zero, ReferenceFrame::kInertial).linear,
              data.origin_acceleration[k]);
    EXPECT_LT((mbk::point_velocity(data, k, r_k, ReferenceFrame::kInertial).linear -
               data.mass_center_velocity[k])
                  .norm(),
              kTol * scale);
    EXPECT_LT((mbk::point_acceleration(data, k, r_k, ReferenceFrame::kInertial).linear -
               data.mass_center_acceleration[k])
                  .norm(),
              kTol * scale);
  }
}

// One body on a hinge about z at angle theta, speed w, acceleration wd, its origin 1 m out
// along x of R: in Bk, omega = (0, 0, w) and alpha = (0, 0, wd) whatever theta; the point at
// r = (1, 0, 0) in Bk, 1 m from the axis, moves on a circle.
TEST(BodyVelocity, BodyFrameComponentsOfAHinge) {
  mbk::Model model = mbk::make_bare_model({0}, mbk::JointType::kRevolute);
  model.bodies[1].joint.offset = V(1, 0, 0);
  model.bodies[1].joint.axis = V::UnitZ();
  mbk::finalize_model(model);
  mbk::JointState<double> state(model);
  const double theta = 0.9, w = 2.0, wd = -3.0;
  state.position[0] = theta;
  state.velocity[0] = w;
  state.acceleration[0] = wd;
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  const V r(1, 0, 0);
  const auto v = mbk::point_velocity(data, 1, r, ReferenceFrame::kBody);
  const auto a = mbk::point_acceleration(data, 1, r, ReferenceFrame::kBody);
  EXPECT_LT((v.angular - V(0, 0, w)).norm(), kTol);
  EXPECT_LT((a.angular - V(0, 0, wd)).norm(), kTol);
  // In Bk: the point's velocity is w r along y; its acceleration wd r along y, -w^2 r along x.
  EXPECT_LT((v.linear - V(0, w, 0)).norm(), kTol);
  EXPECT_LT((a.linear - V(-w * w, wd, 0)).norm(), kTol);
  // And in R: the same vectors turned by S0K (theta about z).
  const mbk::Mat3<double> s0k = Eigen::AngleAxisd(theta, V::UnitZ()).toRotationMatrix();
  EXPECT_LT(
      (mbk::point_velocity(data, 1, r, ReferenceFrame::kInertial).linear - s0k * v.linear).norm(),
      kTol);
  EXPECT_LT((mbk::point_acceleration(data, 1, r, ReferenceFrame::kInertial).linear - s0k * a.linear)
                .norm(),
            kTol);
}

}  // namespace
