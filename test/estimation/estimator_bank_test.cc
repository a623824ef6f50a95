// Banks of derivative estimators (estimator_bank.h, kalman_bank.h): one sample of many
// coordinates in one call gives each coordinate what its own estimator gives, bit for bit.
#include "mb_kinematics/estimation/estimator_bank.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/estimation/kalman_bank.h"
#include "mb_kinematics/estimation/kalman_estimator.h"

namespace {

// n coordinates of noisy sines, 2000 samples: irregular steps, some stamps repeated, some going
// back, one infinite; some coordinates left out of a sample, some values NaN, some histories reset.
// Each sample goes to `bank` in one call and to one estimator per coordinate (`prototype`'s
// clones); every estimate must be the same bits.
void expect_bank_is_separate_estimators(const mbk::DerivativeEstimator& prototype, int n,
                                        unsigned seed) {
  std::unique_ptr<mbk::EstimatorBank> bank = prototype.bank(n);
  ASSERT_EQ(bank->size(), n);
  std::vector<std::unique_ptr<mbk::DerivativeEstimator>> single;
  for (int i = 0; i < n; ++i) single.push_back(prototype.clone());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(n);
  std::vector<char> use(n);
  double t = 0;
  for (int k = 0; k < 2000; ++k) {
    const double r = u(rng);
    if (r < 0.03)
      t -= 0.01 * u(rng);  // back
    else if (r > 0.08)     // else repeated
      t += 1e-4 + 2e-2 * u(rng);
    const double stamp = k == 1000 ? INFINITY : t;
    for (int i = 0; i < n; ++i) {
      x[i] = u(rng) < 0.002 ? NAN : std::sin(3 * t + i) + 1e-3 * (u(rng) - 0.5);
      use[i] = u(rng) < 0.85;
      if (u(rng) < 0.003) single[i]->reset(), bank->reset(i);
      if (use[i]) single[i]->add(stamp, x[i]);
    }
    bank->add(stamp, x.data(), use.data());
    bool all = true;
    std::vector<double> first(n), second(n);
    for (int i = 0; i < n; ++i) {
      double a[2] = {0, 0}, b[2] = {0, 0};
      const int valid = single[i]->estimate(b[0], b[1]);
      ASSERT_EQ(bank->estimate(i, a[0], a[1]), valid) << k << " " << i;
      ASSERT_EQ(std::memcmp(a, b, sizeof a), 0) << k << " " << i << ": " << a[0] << " " << b[0];
      all = all && valid == 2;
      first[i] = b[0], second[i] = b[1];
    }
    // all_estimated: every estimate whole, or nothing written.
    std::vector<double> whole_first(n, -7.0), whole_second(n, -7.0);
    ASSERT_EQ(bank->all_estimated(whole_first.data(), whole_second.data()), all) << k;
    EXPECT_EQ(whole_first, all ? first : std::vector<double>(n, -7.0)) << k;
    EXPECT_EQ(whole_second, all ? second : std::vector<double>(n, -7.0)) << k;
    // Without the second derivatives' array: the first ones alone.
    std::vector<double> first_only(n, -7.0);
    ASSERT_EQ(bank->all_estimated(first_only.data(), nullptr), all) << k;
    EXPECT_EQ(first_only, whole_first) << k;
  }
}

// 1 to 23 filters: the vectorized pass's full vectors and the ones left over.
TEST(KalmanBank, IsSeparateFiltersBitForBit) {
  for (int n = 1; n <= 23; ++n) {
    expect_bank_is_separate_estimators(mbk::KalmanEstimator(10.0, 1e-4), n, n);
    expect_bank_is_separate_estimators(mbk::KalmanEstimator(1e3, 1e-5), n, 100 + n);
  }
}

TEST(KalmanBank, IsWhatKalmanEstimatorsMake) {  // the node's banks take the vectorized pass
  const std::unique_ptr<mbk::EstimatorBank> bank = mbk::KalmanEstimator(10.0, 1e-4).bank(5);
  const auto* kalman = dynamic_cast<const mbk::KalmanBank*>(bank.get());
  ASSERT_NE(kalman, nullptr);
  EXPECT_EQ(kalman->jerk_density(), 10.0);
  EXPECT_THROW(mbk::KalmanBank(1.0, 0.0, 3), std::invalid_argument);
  EXPECT_THROW(mbk::KalmanBank(NAN, 1e-4, 3), std::invalid_argument);
}

TEST(ClonedBank, IsSeparateEstimators) {
  for (const char* name : {"backward_difference", "central_difference", "savitzky_golay_end_7_2"})
    expect_bank_is_separate_estimators(*mbk::make_derivative_estimator(name), 7, 7);
}

// bounded: false exactly when some used estimator's first `derivatives` estimates go beyond the
// bound (or NaN); estimators not used, or without estimates yet, do not count.
TEST(EstimatorBank, BoundedLooksAtTheUsedEstimates) {
  for (const char* name : {"kalman_smooth", "backward_difference"}) {
    SCOPED_TRACE(name);
    std::unique_ptr<mbk::EstimatorBank> bank = mbk::make_derivative_estimator(name)->bank(6);
    std::vector<char> all(6, 1), none(6, 0), first(6, 0);
    first[0] = 1;
    std::vector<double> x(6, 0.0);
    for (int k = 0; k < 4; ++k) {
      x[0] = k == 3 ? 1e40 : 0.0;  // x' of about 1e42 after the jump at 0.01 s spacing
      bank->add(0.01 * k, x.data(), all.data());
      EXPECT_TRUE(bank->bounded(none.data(), 2, 1e50));
      EXPECT_TRUE(bank->bounded(all.data(), 2, 1e50));
      EXPECT_EQ(bank->bounded(first.data(), 1, 1e30), k < 3) << k;
    }
    bank->add(0, 0.04, 0.0);
    bank->add(0, 0.05, 1e300);
    bank->add(0, 0.06, -1e300);
    EXPECT_FALSE(bank->bounded(first.data(), 2, 1e50));
    EXPECT_TRUE(bank->bounded(none.data(), 2, 1e50));
    bank->reset(0);
    EXPECT_TRUE(bank->bounded(all.data(), 2, 1e50));
  }
}

// KalmanBank's bounded (one loop without branches, vectorized) is the verdict filter by filter,
// from each one's estimates: 23 filters (full vectors and those left over), values now and then
// of 1e300 either way (estimates beyond the bound, infinite or NaN), random filters used.
TEST(KalmanBank, BoundedIsEachFiltersVerdict) {
  const int n = 23;
  mbk::KalmanBank bank(10.0, 1e-4, n);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(n);
  std::vector<char> use(n);
  int outside = 0;
  for (int k = 0; k < 400; ++k) {
    for (int i = 0; i < n; ++i) {
      const double r = u(rng);
      x[i] = r < 0.01 ? 1e300 : r < 0.02 ? -1e300 : std::sin(0.01 * k + i);
      use[i] = u(rng) < 0.9;
    }
    bank.add(0.01 * k, x.data(), use.data());
    for (int i = 0; i < n; ++i)
      if (u(rng) < 0.02) bank.reset(i);
    for (const int derivatives : {1, 2}) {
      bool within = true;
      for (int i = 0; i < n; ++i) {
        double first = 0, second = 0;
        if (!use[i] || bank.estimate(i, first, second) < 2) continue;
        within = within && std::abs(first) <= 1e50 && (derivatives < 2 || std::abs(second) <= 1e50);
      }
      EXPECT_EQ(bank.bounded(use.data(), derivatives, 1e50), within) << k << " " << derivatives;
      outside += !within;
    }
  }
  EXPECT_GT(outside, 10);  // the jumps put some estimates beyond the bound
}

}  // namespace
