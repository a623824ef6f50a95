// The node's cheap error indicators (mb_kinematics/core/error_indicators.h).
#include "mb_kinematics/core/error_indicators.h"

#include <gtest/gtest.h>

#include <cstring>

#include "mb_kinematics/core/kinematics_double.h"
#include "test/support/test_models.h"

namespace {

TEST(ErrorIndicators, OrthonormalityDriftIsRoundingOnlyAndSeesABadRotation) {
  const mbk::Model model = mbk_test::random_tree(40, 3);
  const mbk_test::Trajectory trajectory(model, 5);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, trajectory.at<double>(0.3), data);
  // Products of up to 40 rotations: a few eps per level, far below 1e-13.
  EXPECT_LT(mbk::orthonormality_drift(data), 1e-13);
  data.rotation[7](0, 0) *= 1.001;
  EXPECT_GT(mbk::orthonormality_drift(data), 1e-4);
}

TEST(ErrorIndicators, EulerNormError) {
  mbk::Model model = mbk::make_bare_model({0, 1}, mbk::JointType::kBallEuler);
  mbk::JointState<double> state(model);  // identity: e4 = 1
  EXPECT_EQ(mbk::euler_norm_error(model, state), 0.0);
  state.position[7] = 2.0;  // body 2's e4
  EXPECT_DOUBLE_EQ(mbk::euler_norm_error(model, state), 1.0);
  const mbk::Model hinges = mbk::make_bare_model({0, 1}, mbk::JointType::kRevolute);
  EXPECT_EQ(mbk::euler_norm_error(hinges, mbk::JointState<double>(hinges)), 0.0);
}

TEST(ErrorIndicators, PredictionResidualIsExactForQuadraticsAndSeesAJump) {
  const mbk::Model model = mbk::make_bare_model({0, 1, 2}, mbk::JointType::kRevolute);
  mbk::JointState<double> a(model), b(model);
  const double dt = 0.01;
  for (int i = 0; i < 3; ++i) {  // q = 1 + 2t + 3t^2 from t = 0 to dt
    a.position[i] = 1, a.velocity[i] = 2, a.acceleration[i] = 6;
    b.position[i] = 1 + 2 * dt + 3 * dt * dt;
  }
  EXPECT_LT(mbk::prediction_residual(a, b, dt), 1e-15);
  b.position[1] += 0.5;
  EXPECT_NEAR(mbk::prediction_residual(a, b, dt), 0.5, 1e-15);
}

// prediction_residual in one expression (no vector for the prediction) gives the bits of the
// prediction made first, then the residual's norm, over a trajectory of a chain (nq = nv, as the
// node's models).
TEST(ErrorIndicators, PredictionResidualAsWithThePredictionMadeFirst) {
  const mbk::Model model = mbk_test::revolute_chain(100);
  const mbk_test::Trajectory trajectory(model, 6);
  for (const double dt : {1e-3, 0.01, 0.37}) {
    const mbk::JointState<double> a = trajectory.at<double>(0.2),
                                  b = trajectory.at<double>(0.2 + dt);
    const mbk::VecX<double> predicted =
        a.position + a.velocity * dt + a.acceleration * (dt * dt / 2);
    const double want = (b.position - predicted).lpNorm<Eigen::Infinity>();
    const double got = mbk::prediction_residual(a, b, dt);
    EXPECT_EQ(std::memcmp(&got, &want, sizeof got), 0) << dt << ": " << got << " against " << want;
    EXPECT_GT(got, 0.0);
  }
}

}  // namespace
