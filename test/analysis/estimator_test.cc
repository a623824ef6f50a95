// The estimators of joint velocities and accelerations, and the study that compares them.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "mb_kinematics/analysis/estimator_study.h"
#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/estimation/kalman_estimator.h"
#include "mb_kinematics/estimation/polynomial_fit_estimator.h"
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

// The textbook form of the same filter in long double: s <- F s, P <- F P F^T + q Q,
// K = P e1 / (P00 + r), s += K (x - s0), P -= K P.row(0). KalmanEstimator multiplies F P F^T out
// on P's upper triangle in double.
struct TextbookKalman {
  using Vec = Eigen::Matrix<long double, 3, 1>;
  using Mat = Eigen::Matrix<long double, 3, 3>;
  long double q, r, t = 0;
  Vec s = Vec::Zero();
  Mat p = Mat::Zero();
  void start(long double t0, long double x) {
    t = t0;
    s << x, 0, 0;
    p = Vec(r, 1e6L, 1e12L).asDiagonal();
  }
  void add(long double t1, long double x) {
    const long double dt = t1 - t, d2 = dt * dt, d3 = d2 * dt;
    Mat f, w;
    f << 1, dt, d2 / 2, 0, 1, dt, 0, 0, 1;
    w << d3 * d2 / 20, d2 * d2 / 8, d3 / 6, d2 * d2 / 8, d3 / 3, d2 / 2, d3 / 6, d2 / 2, dt;
    s = f * s;
    p = f * p * f.transpose() + q * w;
    const Vec k = p.col(0) / (p(0, 0) + r);
    s += k * (x - s[0]);
    p -= k * p.row(0);
    t = t1;
  }
};

// Irregular stamps, noisy samples, three jerk densities, 20 seeds: the estimates stay within 2 %
// of the filter's own standard deviation (sqrt of P's diagonal) of the long double filter. The
// filter amplifies rounding (position variance 1e-8 against a starting 1e12): on these runs the
// textbook form in double strays up to 1.41 % of it, this one 1.28 %; a wrong term strays by
// many standard deviations.
TEST(Kalman, AgreesWithTheTextbookFormInLongDouble) {
  std::uniform_real_distribution<double> step(1e-4, 2e-2), noise(-1e-3, 1e-3);
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    for (const double q : {1e-2, 1.0, 1e4}) {
      mbk::KalmanEstimator filter(q, 1e-4);
      TextbookKalman reference{q, 1e-8L};
      double t = 0, first = 0, second = 0;
      for (int i = 0; i < 3000; ++i) {
        if (i > 0) t += step(rng);
        const double x = std::sin(3 * t) + noise(rng);
        filter.add(t, x);
        if (i == 0)
          reference.start(t, x);
        else
          reference.add(t, x);
        if (i < 2) continue;
        ASSERT_EQ(filter.estimate(first, second), 2);
        const double sd1 = std::sqrt(static_cast<double>(reference.p(1, 1)));
        const double sd2 = std::sqrt(static_cast<double>(reference.p(2, 2)));
        ASSERT_NEAR(first, static_cast<double>(reference.s[1]), 2e-2 * sd1) << seed << " " << q;
        ASSERT_NEAR(second, static_cast<double>(reference.s[2]), 2e-2 * sd2) << seed << " " << q;
      }
    }
  }
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
