// The zero-lag Butterworth estimator (estimation/butterworth_estimator.h): Winter's two-pass
// correction, its derivatives against the analytic ones of a sine under noise, the residual
// analysis' noise line and cutoff, error bars that are the estimates' own weights (against
// impulses through the whole estimator, ends included) and cover the true errors at about their
// stated rate. Against scipy.signal.butter/filtfilt: test/python/test_butterworth.py.
#include "mb_kinematics/estimation/butterworth_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace {

// x = 0.4 sin(2 pi 0.5 t) + 0.1 sin(2 pi 2.3 t) (human-like content); d: the derivative's order.
double signal(double t, int d) {
  const double a = 2 * M_PI * 0.5, b = 2 * M_PI * 2.3;
  switch (d) {
    case 0:
      return 0.4 * std::sin(a * t) + 0.1 * std::sin(b * t);
    case 1:
      return 0.4 * a * std::cos(a * t) + 0.1 * b * std::cos(b * t);
    default:
      return -0.4 * a * a * std::sin(a * t) - 0.1 * b * b * std::sin(b * t);
  }
}

struct Stream {
  std::vector<double> t, x;
};

Stream stream(double rate, double seconds, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  Stream s;
  for (int i = 0; i < static_cast<int>(rate * seconds); ++i) {
    s.t.push_back((i + 1) / rate);
    s.x.push_back(signal(s.t.back(), 0) + (noise > 0 ? gauss(rng) : 0.0));
  }
  return s;
}

mbk::AutoEstimate estimate(const std::string& name, const Stream& s) {
  mbk::AutoEstimate a;
  mbk::estimate_butterworth(mbk::make_offline_estimator(name), s.t, s.x.data(), 1, 1, 1.0, a);
  return a;
}

// Largest |error| over samples [from, to) relative to the largest |exact|.
double error(const Stream& s, const std::vector<double>& estimate, int d, size_t from, size_t to) {
  double err = 0, scale = 0;
  for (size_t i = 0; i < s.t.size(); ++i) {
    scale = std::max(scale, std::abs(signal(s.t[i], d)));
    if (i >= from && i < to) err = std::max(err, std::abs(estimate[i] - signal(s.t[i], d)));
  }
  return err / scale;
}

TEST(ButterworthEstimatorTest, WintersCorrectionPutsTheTwoPassesThreeDecibelsDownAtTheCutoff) {
  EXPECT_NEAR(mbk::butterworth_correction(), 0.802, 5e-4);  // Winter's 0.802
  // A sine at FC through both passes, amplitude measured far from the ends: 1 / sqrt(2) of the
  // input's to the pre-warping's difference (tan(pi f / fs) / tan(pi f / (C fs)) is C only as
  // f / fs -> 0): within 1 % at FC / fs = 0.006, 2 % at 0.06.
  for (double rate : {100.0, 1000.0}) {
    const double fc = 6;
    const mbk::Butterworth2 f = mbk::butterworth_lowpass(fc / mbk::butterworth_correction(), rate);
    std::vector<double> x(static_cast<int>(20 * rate)), y(x.size()), scratch;
    for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(2 * M_PI * fc * i / rate);
    mbk::filtfilt(f, x.data(), static_cast<int>(x.size()), y.data(), scratch,
                  mbk::butterworth_padding(f));
    double peak = 0;
    for (size_t i = x.size() / 4; i < 3 * x.size() / 4; ++i) peak = std::max(peak, std::abs(y[i]));
    EXPECT_NEAR(peak, 1 / std::sqrt(2.0), (rate == 100 ? 0.02 : 0.01) / std::sqrt(2.0)) << rate;
  }
}

// Both passes' gain at f Hz, cutoff fc, rate fs: the squared magnitude of the pre-warped
// 2nd-order Butterworth designed at fc / C, 1 / (1 + (tan(pi f / fs) / tan(pi fc / (C fs)))^4).
double two_pass_gain(double f, double fc, double fs) {
  const double ratio =
      std::tan(M_PI * f / fs) / std::tan(M_PI * fc / (mbk::butterworth_correction() * fs));
  return 1 / (1 + std::pow(ratio, 4));
}

TEST(ButterworthEstimatorTest, SineUnderNoiseAgainstItsAnalyticDerivatives) {
  // 1 kHz, 1e-4 of noise on the two sines (0.5 and 2.3 Hz); 0.5 s from the ends.
  const Stream s = stream(1000, 10, 1e-4, 3);
  const size_t inside = 500, n = s.t.size();
  // At 6 Hz (Winter's gait cutoff), against the analytic derivatives of the sines each scaled by
  // the two passes' gain at its frequency: what is left is the noise's share and the differences'.
  const mbk::AutoEstimate six = estimate("butterworth:6", s);
  const double g1 = two_pass_gain(0.5, 6, 1000), g2 = two_pass_gain(2.3, 6, 1000);
  double err[2] = {}, scale[2] = {};
  for (size_t i = 0; i < n; ++i) {
    const double t = s.t[i], a = 2 * M_PI * 0.5, b = 2 * M_PI * 2.3;
    const double v = 0.4 * a * g1 * std::cos(a * t) + 0.1 * b * g2 * std::cos(b * t);
    const double acc = -0.4 * a * a * g1 * std::sin(a * t) - 0.1 * b * b * g2 * std::sin(b * t);
    scale[0] = std::max(scale[0], std::abs(v)), scale[1] = std::max(scale[1], std::abs(acc));
    if (i < inside || i >= n - inside) continue;
    err[0] = std::max(err[0], std::abs(six.first[i] - v));
    err[1] = std::max(err[1], std::abs(six.second[i] - acc));
  }
  EXPECT_LT(err[0] / scale[0], 5e-4);
  EXPECT_LT(err[1] / scale[1], 5e-3);
  EXPECT_NEAR(six.noise[0], 1e-4, 1e-5);
  // butterworth:auto against the raw analytic derivatives (the cutoff it chose passes 2.3 Hz).
  const mbk::AutoEstimate a = estimate("butterworth:auto", s);
  EXPECT_LT(error(s, a.first, 1, inside, n - inside), 2e-3);     // measured 1.5e-3
  EXPECT_LT(error(s, a.second, 2, inside, n - inside), 2.5e-2);  // 1.7e-2
  EXPECT_LT(error(s, a.first, 1, 0, n), 5e-3);                   // ends included
  EXPECT_LT(error(s, a.second, 2, 0, n), 5e-2);
  EXPECT_GT(a.cutoff[0], 6);
}

TEST(ButterworthEstimatorTest, ResidualAnalysisFindsTheNoiseAndACutoffAboveTheSignal) {
  // Winter's noise line's intercept is about the noise's rms; the cutoff rises as noise falls.
  double last = 0;
  for (double noise : {1e-2, 1e-3, 1e-4}) {
    const Stream s = stream(100, 20, noise, 5);
    const mbk::ResidualChoice r = mbk::residual_cutoff(s.x, mbk::find_segments(s.t, 1.0), 100);
    EXPECT_NEAR(r.intercept, noise, 0.15 * noise) << noise;
    EXPECT_GT(r.cutoff, last) << noise;
    EXPECT_GT(r.cutoff, 2.3) << noise;  // the signal's top frequency passes
    last = r.cutoff;
  }
}

TEST(ButterworthEstimatorTest, WeightNormsAreTheEstimatesOwnEndsIncluded) {
  // The estimator is linear in x: its response to a unit impulse at j is column j of the
  // estimate's weights; their squares summed over j are each sample's |w|^2.
  // 600 samples: the ends in closed form, the middle from the responses' autocorrelations; both
  // from responses cut where they fall below e^-12 (their truncation: 2e-6 relative here).
  for (double rate : {100.0, 1000.0}) {
    const int n = 600;
    const std::string name = rate == 100 ? "butterworth:6" : "butterworth:60";
    Stream s;
    for (int i = 0; i < n; ++i) s.t.push_back((i + 1) / rate), s.x.push_back(0);
    std::vector<double> first2(n, 0.0), second2(n, 0.0);
    for (int j = 0; j < n; ++j) {
      s.x.assign(n, 0.0);
      s.x[j] = 1;
      const mbk::AutoEstimate a = estimate(name, s);
      for (int i = 0; i < n; ++i)
        first2[i] += a.first[i] * a.first[i], second2[i] += a.second[i] * a.second[i];
    }
    std::vector<double> first, second;
    mbk::butterworth_weight_norms(rate / 100 * 6, rate, s.t, first, second);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(first[i], first2[i], 1e-5 * first2[i]) << rate << " Hz, sample " << i;
      EXPECT_NEAR(second[i], second2[i], 1e-5 * second2[i]) << rate << " Hz, sample " << i;
    }
  }
}

TEST(ButterworthEstimatorTest, ErrorBarsCoverTheTrueErrors) {
  // Over many noise draws, the share of samples whose true error lies within one stated standard
  // error: about 68 % (between 60 and 90 %), ends included.
  for (double rate : {100.0, 1000.0})
    for (double noise : {1e-4, 1e-3}) {
      long inside[2] = {}, count = 0;
      for (unsigned seed = 1; seed <= 10; ++seed) {
        const Stream s = stream(rate, 4, noise, seed);
        const mbk::AutoEstimate a = estimate("butterworth:auto", s);
        for (size_t i = 0; i < s.t.size(); ++i, ++count) {
          inside[0] += std::abs(a.first[i] - signal(s.t[i], 1)) <= a.first_se[i];
          inside[1] += std::abs(a.second[i] - signal(s.t[i], 2)) <= a.second_se[i];
        }
      }
      for (int d = 0; d < 2; ++d) {
        const double share = static_cast<double>(inside[d]) / count;
        EXPECT_GT(share, 0.60) << rate << " Hz, noise " << noise << ", derivative " << d + 1;
        EXPECT_LT(share, 0.90) << rate << " Hz, noise " << noise << ", derivative " << d + 1;
      }
    }
}

TEST(ButterworthEstimatorTest, NamesAndBadCutoffs) {
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("butterworth:6");
  EXPECT_TRUE(e.butterworth && e.whole_series() && !e.automatic);
  EXPECT_EQ(e.cutoff, 6);
  EXPECT_EQ(mbk::make_offline_estimator("butterworth:auto").cutoff, 0);
  mbk::OfflineReach reach;
  EXPECT_FALSE(mbk::offline_reach(e, reach));  // a recursive filter reaches every sample
  for (const char* bad : {"butterworth:", "butterworth:0", "butterworth:-3", "butterworth:6x",
                          "butterworth:nan", "butterworth:inf", "butterworth"})
    EXPECT_THROW(mbk::make_offline_estimator(bad), std::invalid_argument) << bad;
  // A cutoff the rate cannot hold: one line naming the limit.
  const Stream s = stream(100, 2, 0, 1);
  try {
    estimate("butterworth:45", s);
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("butterworth:45: the cutoff must be below 40.1"),
              std::string::npos)
        << error.what();
  }
}

TEST(ButterworthEstimatorTest, SegmentsAreFilteredApartAndShortOnesAreMarked) {
  // A gap splits the series: each side is filtered on its own (the same as alone), a lone
  // sample has no derivative, two have a velocity only.
  Stream s = stream(100, 3, 1e-4, 2);
  Stream left;
  left.t.assign(s.t.begin(), s.t.begin() + 150), left.x.assign(s.x.begin(), s.x.begin() + 150);
  for (size_t i = 150; i < s.t.size(); ++i) s.t[i] += 1;  // a 1 s gap
  s.t.push_back(s.t.back() + 2), s.x.push_back(0);        // a lone sample
  mbk::AutoEstimate whole, alone;
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("butterworth:6");
  mbk::estimate_butterworth(e, s.t, s.x.data(), 1, 1, 0.5, whole);
  mbk::estimate_butterworth(e, left.t, left.x.data(), 1, 1, 0.5, alone);
  for (size_t i = 0; i < left.t.size(); ++i) {
    EXPECT_NEAR(whole.first[i], alone.first[i], 1e-12) << i;
    EXPECT_NEAR(whole.second[i], alone.second[i], 1e-9) << i;
  }
  EXPECT_EQ(whole.valid[150], 2);
  EXPECT_EQ(whole.valid.back(), 0);
}

}  // namespace
