// The 3-point backward-difference estimator against closed forms (doc/method.md 8).
#include "mb_kinematics/estimation/derivative_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace {

std::unique_ptr<mbk::DerivativeEstimator> make() {
  return mbk::make_derivative_estimator("backward_difference");
}

TEST(DerivativeEstimatorTest, ExactForQuadraticsOnIrregularTimes) {
  auto e = make();
  auto x = [](double t) { return 1.5 - 0.7 * t + 0.3 * t * t; };
  double first = 0, second = 0;
  EXPECT_EQ(e->estimate(first, second), 0);
  const double times[] = {0.0, 0.013, 0.031, 0.04, 0.071};
  for (int i = 0; i < 5; ++i) {
    e->add(times[i], x(times[i]));
    const int n = e->estimate(first, second);
    EXPECT_EQ(n, std::min(i, 2));
    if (n >= 1 && i >= 2) {
      EXPECT_NEAR(first, -0.7 + 0.6 * times[i], 1e-10);
    }
    if (n == 2) {
      EXPECT_NEAR(second, 0.6, 1e-8);
    }
  }
}

TEST(DerivativeEstimatorTest, ConvergesOnSmoothSignals) {  // first O(h^2), second O(h)
  double errors[2][2];
  for (int r = 0; r < 2; ++r) {
    const double h = r == 0 ? 1e-2 : 5e-3;
    auto e = make();
    for (int i = 0; i < 3; ++i) e->add(1 + i * h, std::sin(1 + i * h));
    double first = 0, second = 0;
    ASSERT_EQ(e->estimate(first, second), 2);
    const double t = 1 + 2 * h;
    errors[r][0] = std::abs(first - std::cos(t));
    errors[r][1] = std::abs(second + std::sin(t));
  }
  EXPECT_NEAR(errors[0][0] / errors[1][0], 4.0, 0.3);
  EXPECT_NEAR(errors[0][1] / errors[1][1], 2.0, 0.2);
}

TEST(DerivativeEstimatorTest, BackwardsResetsEqualReplacesNonFiniteIgnored) {
  auto e = make();
  double first = 0, second = 0;
  e->add(1.0, 1.0);
  e->add(2.0, 2.0);
  EXPECT_TRUE(e->add(2.0, 4.0));  // replaces the sample at t = 2
  EXPECT_EQ(e->estimate(first, second), 1);
  EXPECT_DOUBLE_EQ(first, 3.0);
  EXPECT_FALSE(e->add(NAN, 1.0));
  EXPECT_FALSE(e->add(3.0, INFINITY));
  EXPECT_EQ(e->estimate(first, second), 1);
  EXPECT_FALSE(e->add(0.5, 0.0));  // backwards: a fresh history holding this sample
  EXPECT_EQ(e->estimate(first, second), 0);
  auto copy = e->clone();
  EXPECT_EQ(copy->estimate(first, second), 0);
  EXPECT_THROW(mbk::make_derivative_estimator("magic"), std::invalid_argument);
}

}  // namespace
