// The estimators of joint velocities and accelerations, and the study that compares them.
#include <gtest/gtest.h>

#include <cmath>

#include "mb_kinematics/analysis/estimator_study.h"
#include "mb_kinematics/core/derivative_estimator.h"
#include "mb_kinematics/core/kalman_estimator.h"
#include "mb_kinematics/core/polynomial_fit_estimator.h"
#include "mb_kinematics/io/load_model.h"

namespace {

// A least-squares polynomial of order p reproduces any polynomial of degree <= p exactly, on
// irregular stamps, at every latency: derivatives to rounding.
TEST(PolynomialFit, ExactForPolynomialsOnIrregularStamps) {
  for (int latency : {0, 2, 4}) {
    mbk::PolynomialFitEstimator fit(7, 3, latency);
    std::vector<double> t;
    for (int i = 0; i < 12; ++i) t.push_back(0.01 * i + 0.003 * std::sin(7.0 * i));
    auto x = [](double s) { return 1 - 2 * s + 3 * s * s - 4 * s * s * s; };
    double first = 0, second = 0;
    for (double s : t) fit.add(s, x(s));
    ASSERT_EQ(fit.estimate(first, second), 2);
    const double te = t[t.size() - 1 - latency];
    EXPECT_NEAR(first, -2 + 6 * te - 12 * te * te, 1e-9) << "latency " << latency;
    EXPECT_NEAR(second, 6 - 24 * te, 1e-6) << "latency " << latency;
    EXPECT_EQ(fit.latency(), latency);
  }
}

TEST(PolynomialFit, BackwardStampsResetAndBadSettingsAreRejected) {
  mbk::PolynomialFitEstimator fit(3, 2, 0);
  double first, second;
  EXPECT_TRUE(fit.add(0.0, 0.0));
  EXPECT_TRUE(fit.add(0.1, 1.0));
  EXPECT_TRUE(fit.add(0.2, 4.0));
  EXPECT_EQ(fit.estimate(first, second), 2);
  EXPECT_FALSE(fit.add(0.05, 1.0));  // a bag looping
  EXPECT_EQ(fit.estimate(first, second), 0);
  EXPECT_FALSE(fit.add(0.3, NAN));
  EXPECT_THROW(mbk::PolynomialFitEstimator(3, 3, 0), std::invalid_argument);
  EXPECT_THROW(mbk::PolynomialFitEstimator(5, 2, 5), std::invalid_argument);
  EXPECT_THROW(mbk::KalmanEstimator(0.0, 1e-6), std::invalid_argument);
}

TEST(Kalman, TracksAParabola) {
  mbk::KalmanEstimator filter(1.0, 1e-6);
  double first = 0, second = 0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = 1e-3 * i;
    filter.add(t, 0.5 * 3.0 * t * t + 2 * t);
  }
  ASSERT_EQ(filter.estimate(first, second), 2);
  // Constant acceleration is the filter's own model: after 2 s it has converged to well
  // within 1e-3 of x'' = 3 and x' = 2 + 3 t.
  EXPECT_NEAR(second, 3.0, 1e-3);
  EXPECT_NEAR(first, 2.0 + 3.0 * 2.0, 1e-3);
}

// On the demo's smooth, noise-free trajectories (human body model) every estimator's error
// shrinks as the rate grows; the 3-point differences by the factor their order predicts
// (second derivative: backward O(h), central O(h^2)).
TEST(EstimatorStudy, ErrorShrinksAsTheRateGrows) {
  const std::vector<mbk::Wave> waves = mbk::demo_waves(
      mbk::load_model_file(std::string(MBK_SOURCE_DIR) + "/config/human_body.yaml"));
  for (const std::string& name : mbk::derivative_estimator_names()) {
    const double slow = mbk::run_estimator(name, waves, 100, 0, 0, 4, 1).error;
    const double fast = mbk::run_estimator(name, waves, 1000, 0, 0, 4, 1).error;
    EXPECT_LT(fast, slow) << name;
  }
  const double b100 = mbk::run_estimator("backward_difference", waves, 100, 0, 0, 4, 1).error;
  const double b1000 = mbk::run_estimator("backward_difference", waves, 1000, 0, 0, 4, 1).error;
  EXPECT_NEAR(b100 / b1000, 10.0, 2.0);
  const double c100 = mbk::run_estimator("central_difference", waves, 100, 0, 0, 4, 1).error;
  const double c1000 = mbk::run_estimator("central_difference", waves, 1000, 0, 0, 4, 1).error;
  EXPECT_NEAR(c100 / c1000, 100.0, 20.0);
}

TEST(EstimatorStudy, EveryEstimatorHasAName) {
  for (const std::string& name : mbk::derivative_estimator_names())
    EXPECT_NO_THROW(mbk::make_derivative_estimator(name)) << name;
  EXPECT_THROW(mbk::make_derivative_estimator("no_such"), std::invalid_argument);
}

}  // namespace
