// The propagated error bars of the bodies' accelerations (core/body_errors.h) against Monte
// Carlo: joint velocities and accelerations drawn around a state with their stated standard
// errors, the spread of every body's alpha and mass-center acceleration (forward_kinematics)
// matches the propagated sigma within 10 %, on a chain of ball joints and on a random tree of
// every joint type.
#include "mb_kinematics/core/body_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"

namespace {

void check_against_monte_carlo(const mbk::Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  const mbk::JointState<double> state = mbk::random_state(model, rng);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  Eigen::VectorXd velocity_se(model.nv), acceleration_se(model.nv);
  for (int r = 0; r < model.nv; ++r)
    velocity_se[r] = 1e-3 * u(rng), acceleration_se[r] = 1e-3 * u(rng);
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> data(model);
  mbk::partial_velocity_kinematics(model, state, pv, data);
  std::vector<mbk::Vec3<double>> alpha_se, a_se;
  mbk::body_acceleration_errors(model, pv, data, velocity_se.data(), acceleration_se.data(),
                                alpha_se, a_se);

  const int n = model.body_count(), draws = 4000;
  std::vector<mbk::Vec3<double>> alpha_var(n + 1, mbk::Vec3<double>::Zero()), a_var = alpha_var;
  std::normal_distribution<double> gauss(0.0, 1.0);
  mbk::JointState<double> drawn = state;
  mbk::Data<double> d(model);
  for (int s = 0; s < draws; ++s) {
    for (int r = 0; r < model.nv; ++r) {
      drawn.velocity[r] = state.velocity[r] + velocity_se[r] * gauss(rng);
      drawn.acceleration[r] = state.acceleration[r] + acceleration_se[r] * gauss(rng);
    }
    mbk::forward_kinematics(model, drawn, d);
    for (int k = 1; k <= n; ++k) {
      alpha_var[k] += (d.alpha[k] - data.alpha[k]).array().square().matrix() / draws;
      a_var[k] += (d.mass_center_acceleration[k] - data.mass_center_acceleration[k])
                      .array()
                      .square()
                      .matrix() /
                  draws;
    }
  }
  for (int k = 1; k <= n; ++k)
    for (int x = 0; x < 3; ++x) {
      // 4000 draws: the sample standard deviation is within about 3.5 % (3 sigma).
      if (alpha_se[k][x] > 1e-9) {
        EXPECT_NEAR(std::sqrt(alpha_var[k][x]) / alpha_se[k][x], 1.0, 0.1) << "alpha " << k << x;
      }
      if (a_se[k][x] > 1e-9) {
        EXPECT_NEAR(std::sqrt(a_var[k][x]) / a_se[k][x], 1.0, 0.1) << "a " << k << x;
      }
    }
}

TEST(BodyErrorsTest, BallChainMatchesMonteCarlo) {
  check_against_monte_carlo(mbk::make_chain(4, mbk::JointType::kBall123), 1);
}

TEST(BodyErrorsTest, RandomTreeMatchesMonteCarlo) {
  check_against_monte_carlo(mbk::make_random_tree(8, 3), 2);
}

// Streamed (each body's errors as its columns are done, PartialVelocities(model, kStreamed)):
// the same numbers, bit for bit, as from the whole arrays, in memory for the bodies alive at
// once: 2 slots of the deepest body on a chain (the whole arrays: N (N + 1) / 2 columns).
TEST(BodyErrorsTest, StreamedEqualsTheWholeArraysInMemoryOfTheBodiesAlive) {
  for (const mbk::Model& model :
       {mbk::make_random_tree(60, 4), mbk::make_chain(300, mbk::JointType::kRevolute),
        mbk::make_chain(20, mbk::JointType::kBall123)}) {
    std::mt19937 rng(5);
    const mbk::JointState<double> state = mbk::random_state(model, rng);
    std::vector<double> velocity_se(model.nv), acceleration_se(model.nv);
    for (int r = 0; r < model.nv; ++r) velocity_se[r] = 1e-3 * (r + 1), acceleration_se[r] = 1e-2;
    mbk::PartialVelocities<double> whole(model), streamed(model, mbk::kStreamed);
    mbk::Data<double> data(model), streamed_data(model);
    mbk::partial_velocity_kinematics(model, state, whole, data);
    std::vector<mbk::Vec3<double>> alpha_se, a_se, streamed_alpha_se, streamed_a_se;
    mbk::body_acceleration_errors(model, whole, data, velocity_se.data(), acceleration_se.data(),
                                  alpha_se, a_se);
    for (int twice = 0; twice < 2; ++twice)  // its slots come back for the next state
      mbk::body_acceleration_errors(model, state, streamed, streamed_data, velocity_se.data(),
                                    acceleration_se.data(), streamed_alpha_se, streamed_a_se);
    EXPECT_EQ(streamed_alpha_se, alpha_se);
    EXPECT_EQ(streamed_a_se, a_se);
    EXPECT_EQ(streamed_data.omega, data.omega);  // DataSums::kOmega: omega_k, not alpha_k
    EXPECT_EQ(streamed_data.rotation, data.rotation);
    EXPECT_LT(streamed.entries(), whole.entries());
  }
  const mbk::Model chain = mbk::make_chain(300, mbk::JointType::kRevolute);
  EXPECT_EQ(mbk::PartialVelocities<double>(chain).entries(), 300u * 301 / 2);
  EXPECT_EQ(mbk::PartialVelocities<double>(chain, mbk::kStreamed).entries(), 2u * 300);
}

}  // namespace
