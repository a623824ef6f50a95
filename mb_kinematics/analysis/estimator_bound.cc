#include "mb_kinematics/analysis/estimator_bound.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "mb_kinematics/analysis/estimator_study.h"

namespace mbk {

namespace {

constexpr int kMinDegree = 2, kMaxDegree = 6;
// Window lengths tried: from the degree's least (degree + 3 samples) up by this ratio (odd).
constexpr double kWindowRatio = 1.08;

// The windows tried at `rate` Hz: odd sample counts from 5 up to one second's.
std::vector<int> window_lengths(double rate) {
  std::vector<int> out;
  for (double n = 5; n <= rate + 1; n *= kWindowRatio) {
    const int odd = static_cast<int>(n) | 1;
    if (out.empty() || odd > out.back()) out.push_back(odd);
  }
  return out;
}

// The second derivative's weights at t[i] of the degree-d least-squares polynomial through rows
// [begin, end): in s = (t_j - mid) / half (centred for conditioning), x''(t_i) = v^T G^-1 A^T x
// with G = A^T A and v_c = c (c - 1) s_i^(c - 2) / half^2, so w = A G^-1 v.
void second_weights(const std::vector<double>& t, int begin, int end, int i, int d,
                    std::vector<double>& w) {
  const double mid = (t[begin] + t[end - 1]) / 2, half = (t[end - 1] - t[begin]) / 2;
  Eigen::VectorXd moment = Eigen::VectorXd::Zero(2 * d + 1);
  for (int j = begin; j < end; ++j) {
    const double s = (t[j] - mid) / half;
    double p = 1;
    for (int k = 0; k <= 2 * d; ++k, p *= s) moment[k] += p;
  }
  Eigen::MatrixXd g(d + 1, d + 1);
  for (int a = 0; a <= d; ++a)
    for (int b = 0; b <= d; ++b) g(a, b) = moment[a + b];
  const double si = (t[i] - mid) / half;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(d + 1);
  for (int c = 2; c <= d; ++c) v[c] = c * (c - 1) * std::pow(si, c - 2) / (half * half);
  const Eigen::VectorXd coef = g.ldlt().solve(v);
  w.resize(end - begin);
  for (int j = begin; j < end; ++j) {
    const double s = (t[j] - mid) / half;
    double p = 1, sum = 0;
    for (int c = 0; c <= d; ++c, p *= s) sum += p * coef[c];
    w[j - begin] = sum;
  }
}

// A sample window of n rows for sample i of count: centred, shifted at the ends.
int window_begin(int i, int n, int count) { return std::clamp(i - n / 2, 0, count - n); }

struct Best {
  double mse = std::numeric_limits<double>::infinity();
  int n = 0, d = 0;
};

// The bias of weights w on rows [begin, ...) at sample i for wave c: on its own phase (the clean
// samples), or the largest over every phase (phase_blind): for x = b + a sin(w t + p),
// a |sum_j w_j e^(i w t_j) + w^2 e^(i w t_i)| (turn[j * m + c] = e^(i w_c t_j)).
double bias_of(const std::vector<double>& t, const std::vector<double>& clean,
               const std::vector<std::complex<double>>& turn, const Wave& wave, int m, int c,
               int begin, int i, const std::vector<double>& w, bool phase_blind) {
  if (phase_blind) {
    std::complex<double> sum = wave.w * wave.w * turn[static_cast<size_t>(i) * m + c];
    for (size_t j = 0; j < w.size(); ++j) sum += w[j] * turn[(begin + j) * m + c];
    return std::abs(wave.a) * std::abs(sum);
  }
  double fit = 0;
  for (size_t j = 0; j < w.size(); ++j) fit += w[j] * clean[(begin + j) * m + c];
  return fit - wave.at(t[i], 2);
}

// At sample i: each coordinate's best member (expected squared error) into best.
void best_members(const std::vector<double>& t, const std::vector<double>& clean,
                  const std::vector<std::complex<double>>& turn, const std::vector<Wave>& waves,
                  double sigma, const std::vector<int>& lengths, int i, bool phase_blind,
                  std::vector<Best>& best) {
  const int count = static_cast<int>(t.size()), m = static_cast<int>(waves.size());
  std::fill(best.begin(), best.end(), Best{});
  std::vector<double> w;
  for (int n : lengths) {
    if (n > count) break;
    const int begin = window_begin(i, n, count);
    for (int d = kMinDegree; d <= std::min(kMaxDegree, n - 3); ++d) {
      second_weights(t, begin, begin + n, i, d, w);
      double norm2 = 0;
      for (double v : w) norm2 += v * v;
      for (int c = 0; c < m; ++c) {
        const double bias = bias_of(t, clean, turn, waves[c], m, c, begin, i, w, phase_blind);
        const double mse = bias * bias + sigma * sigma * norm2;
        if (mse < best[c].mse) best[c] = {mse, n, d};
      }
    }
  }
}

}  // namespace

OracleBound local_polynomial_oracle(const std::vector<Wave>& waves, double rate, double jitter,
                                    double noise, double seconds, double margin, int inside_stride,
                                    bool phase_blind) {
  std::vector<double> t, x, tc, clean;
  study_stream(waves, rate, jitter, noise, seconds, t, x);
  study_stream(waves, rate, jitter, 0, seconds, tc, clean);  // the same stamps, no noise
  const int count = static_cast<int>(t.size()), m = static_cast<int>(waves.size());
  double scale = 0;
  for (int i = 0; i < count; ++i)
    for (int c = 0; c < m; ++c) scale = std::max(scale, std::abs(waves[c].at(t[i], 2)));
  std::vector<std::complex<double>> turn(clean.size());
  for (int i = 0; i < count; ++i)
    for (int c = 0; c < m; ++c) turn[i * m + c] = std::polar(1.0, waves[c].w * t[i]);
  const std::vector<int> lengths = window_lengths(rate);
  std::vector<Best> best(m);
  std::vector<double> w;
  OracleBound out;
  for (int i = 0; i < count; ++i) {
    const bool inside = t[i] >= t.front() + margin && t[i] <= t.back() - margin;
    if (inside && (inside_stride <= 0 || i % inside_stride != 0)) continue;
    best_members(t, clean, turn, waves, noise, lengths, i, phase_blind, best);
    double& error = inside ? out.inside : out.ends;
    double& rms = inside ? out.inside_rms : out.ends_rms;
    for (int c = 0; c < m; ++c) {
      const int begin = window_begin(i, best[c].n, count);
      second_weights(t, begin, begin + best[c].n, i, best[c].d, w);
      double estimate = 0;
      for (int j = 0; j < best[c].n; ++j) estimate += w[j] * x[(begin + j) * m + c];
      error = std::max(error, std::abs(estimate - waves[c].at(t[i], 2)) / scale);
      rms = std::max(rms, std::sqrt(best[c].mse) / scale);
    }
  }
  return out;
}

}  // namespace mbk
