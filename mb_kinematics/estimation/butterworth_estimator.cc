#include "mb_kinematics/estimation/butterworth_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>

namespace mbk {

namespace {

constexpr int kPad = 9;           // the least padding (scipy.signal.filtfilt's default, 2nd order)
constexpr double kPadDecay = 6;   // padding: 6 / (1 - r) samples (r: the poles' radius)
constexpr double kLowest = 1e-3;  // of the rate: the lowest cutoff residual analysis tries
constexpr double kFitFrom = 0.4;  // the noise line is fitted from this fraction of C x Nyquist
constexpr double kFitTo = 0.7;    // to this one (also the highest cutoff chosen)
constexpr double kStepTop = 0.9;  // of C x Nyquist: the highest cutoff of the bias step
constexpr int kFitPoints = 10;    // residuals on the noise line's range
constexpr int kBisections = 30;   // of log(cutoff), for R(cutoff) = intercept
constexpr double kDecay = 12;     // responses counted over 12 / (1 - r) samples: r^d < 7e-6
constexpr int kFilterSeriesPerThread = 4;

// One pass in place over v[0..n), from the state zi * v[0] (forward) or zi * v[n - 1] (backward).
void pass(const Butterworth2& f, double* v, int n, bool backward) {
  if (n == 0) return;
  const int step = backward ? -1 : 1;
  double* p = backward ? v + n - 1 : v;
  double z0 = f.zi[0] * *p, z1 = f.zi[1] * *p;
  for (int i = 0; i < n; ++i, p += step) {
    const double x = *p, y = f.b[0] * x + z0;
    z0 = f.b[1] * x - f.a[1] * y + z1;
    z1 = f.b[2] * x - f.a[2] * y;
    *p = y;
  }
}

// The two passes' response to a unit impulse far from any end (zero states), g[L + d], |d| <= L.
std::vector<double> two_pass_response(const Butterworth2& f, int L) {
  std::vector<double> g(2 * L + 1, 0.0);
  g[L] = 1;
  Butterworth2 zero = f;
  zero.zi[0] = zero.zi[1] = 0;
  pass(zero, g.data(), 2 * L + 1, false);
  pass(zero, g.data(), 2 * L + 1, true);
  return g;
}

// sum_j g[j] g[j + m] for m = 0..kNodes - 1 (g symmetric).
constexpr int kNodes = 5;  // the differences' stencil
struct Autocorrelation {
  double at[kNodes] = {};
};
Autocorrelation autocorrelation(const std::vector<double>& g) {
  Autocorrelation a;
  const int n = static_cast<int>(g.size());
  for (int m = 0; m < kNodes; ++m)
    for (int j = 0; j + m < n; ++j) a.at[m] += g[j] * g[j + m];
  return a;
}

// Samples over which a response of f counts (its poles' radius r: r^d < e^-kDecay).
int response_length(const Butterworth2& f) {
  const double r = std::sqrt(std::max(0.0, f.a[2]));
  return static_cast<int>(std::ceil(kDecay / std::max(1e-6, 1 - r)));
}

// The 5-point difference weights of local row i of a segment of n samples at stamps t[0..n)
// (central inside, one-sided at the ends; fewer points in a shorter segment): the derivatives
// at t_i of the polynomial through those samples, x'(t_i) = sum_k first[k] y[row + k], likewise
// x''.
struct Difference {
  int row = 0, count = 0;
  double first[kNodes] = {}, second[kNodes] = {};
};
Difference difference(const double* t, int n, int i) {
  Difference d;
  d.count = std::min(kNodes, n);
  if (d.count < 2) return d;
  d.row = std::clamp(i - d.count / 2, 0, n - d.count);
  double s[kNodes];
  for (int k = 0; k < d.count; ++k) s[k] = t[d.row + k] - t[i];
  // Lagrange's basis polynomial of node k, prod_j (s - s_j) / (s_k - s_j) over j != k,
  // differentiated once and twice at s = 0.
  for (int k = 0; k < d.count; ++k) {
    double den = 1, first = 0, second = 0;
    for (int j = 0; j < d.count; ++j) {
      if (j == k) continue;
      den *= s[k] - s[j];
      double pj = 1;  // prod over l != k, j of (0 - s_l)
      for (int l = 0; l < d.count; ++l)
        if (l != k && l != j) pj *= -s[l];
      first += pj;
      for (int l = 0; l < d.count; ++l) {
        if (l == k || l == j) continue;
        double pjl = 1;
        for (int q = 0; q < d.count; ++q)
          if (q != k && q != j && q != l) pjl *= -s[q];
        second += pjl;
      }
    }
    d.first[k] = first / den, d.second[k] = second / den;
  }
  return d;
}

// ||D W row i||^2 of a row far from the ends (a full stencil): sum_kl D_ik D_il G(k - l).
double interior_norm2(const double* w, const Autocorrelation& g) {
  double sum = 0;
  for (int k = 0; k < kNodes; ++k)
    for (int l = 0; l < kNodes; ++l) sum += w[k] * w[l] * g.at[std::abs(k - l)];
  return sum;
}

// One series' error bar sums per local row of a segment: |w|^2 of the estimate at FC and of its
// step to 2 FC, for both derivatives.
struct RowSums {
  std::vector<double> w2[2], step2[2];
  void resize(int n) {
    for (int d = 0; d < 2; ++d) w2[d].assign(n, 0.0), step2[d].assign(n, 0.0);
  }
};

// The estimate's filters: at FC, at 2 FC (the bias step), both padded by FC's padding p.
struct Filters {
  Butterworth2 fc, twice;
  bool has_twice = false;
  int pad = 0, length = 0;  // p = FC's response length L (at least kPad)
  // The two-pass responses g[L2 + d], |d| <= L2 = 2 L + kNodes: FC's, FC's less 2 FC's; their
  // autocorrelations; S[j] = sum_{d = j + 1}^{j + p} g(d) for j in [0, L2].
  std::vector<double> g[2], S[2];
  Autocorrelation G[2];
};

Filters make_filters(double cutoff, double rate) {
  const double C = butterworth_correction(), twice = std::min(2 * cutoff, kStepTop * C * rate / 2);
  Filters f;
  f.fc = butterworth_lowpass(cutoff / C, rate);
  f.has_twice = twice > 1.05 * cutoff;
  if (f.has_twice) f.twice = butterworth_lowpass(twice / C, rate);
  f.length = response_length(f.fc);
  f.pad = std::max(kPad, f.length);
  const int L2 = 2 * f.length + kNodes;
  f.g[0] = two_pass_response(f.fc, L2);
  f.g[1] = f.g[0];
  if (f.has_twice) {
    const std::vector<double> g2 = two_pass_response(f.twice, L2);
    for (size_t j = 0; j < g2.size(); ++j) f.g[1][j] -= g2[j];
  } else {
    std::fill(f.g[1].begin(), f.g[1].end(), 0.0);
  }
  for (int o = 0; o < 2; ++o) {
    f.G[o] = autocorrelation(f.g[o]);
    f.S[o].assign(L2 + 1, 0.0);
    for (int j = 0; j <= L2; ++j)
      for (int d = j + 1; d <= std::min(j + f.pad, L2); ++d) f.S[o][j] += f.g[o][L2 + d];
  }
  return f;
}

// Exact sums of every row of a segment (stamps t[0..n), its differences dif) from the filters'
// responses to a unit impulse at each sample: a short segment's.
void exact_sums(const Filters& f, const std::vector<Difference>& dif, int n, RowSums& sums) {
  std::vector<double> y1(n), y2(n), scratch;
  for (int c = 0; c < n; ++c) {
    std::fill(y1.begin(), y1.end(), 0.0);
    y1[c] = 1;
    y2 = y1;
    filtfilt(f.fc, y1.data(), n, y1.data(), scratch, f.pad);
    if (f.has_twice) filtfilt(f.twice, y2.data(), n, y2.data(), scratch, f.pad);
    for (int i = 0; i < n; ++i) {
      const Difference& d = dif[i];
      double v[2] = {}, s[2] = {};
      for (int k = 0; k < d.count; ++k) {
        const int at = d.row + k;
        v[0] += d.first[k] * y1[at], v[1] += d.second[k] * y1[at];
        const double step = f.has_twice ? y1[at] - y2[at] : 0.0;
        s[0] += d.first[k] * step, s[1] += d.second[k] * step;
      }
      for (int q = 0; q < 2; ++q) sums.w2[q][i] += v[q] * v[q], sums.step2[q][i] += s[q] * s[q];
    }
  }
}

// |w|^2 of row i (stencil d) within L of the left end of a long segment, of the operator whose
// two-pass response is g (g[L2 + x]), padded by odd reflection over p >= L samples (the passes'
// starting transients have decayed before the data): column c's weights are
//   W_ic = g(i - c) - [1 <= c <= p] g(i + c) + [c = 0] 2 S(i),
// so with F(c) = sum_k D_ik g(k - c), |w|^2 = sum_kl D_ik D_il G(k - l) + 4 DS (F(0) + DS)
// - 2 sum_{c >= 1} F(c) F(-c), DS = sum_k D_ik S(k).
double left_norm2(const double* w, const Difference& d, const std::vector<double>& g,
                  const std::vector<double>& S, const Autocorrelation& G) {
  const int L2 = static_cast<int>(S.size()) - 1;
  auto at = [&](int x) { return std::abs(x) <= L2 ? g[L2 + x] : 0.0; };
  auto F = [&](int c) {
    double sum = 0;
    for (int k = 0; k < d.count; ++k) sum += w[k] * at(d.row + k - c);
    return sum;
  };
  double DS = 0, cross = 0;
  for (int k = 0; k < d.count; ++k) DS += w[k] * S[std::min(d.row + k, L2)];
  const int L = (L2 - kNodes) / 2;  // beyond L the responses have decayed
  for (int c = 1; c <= L - d.row + kNodes; ++c) cross += F(c) * F(-c);
  return interior_norm2(w, G) + 4 * DS * (F(0) + DS) - 2 * cross;
}

// The sums of every row of a segment: within L of an end in closed form (left_norm2; the right
// end as the left one of the reversed segment), from the responses' autocorrelations elsewhere;
// a segment shorter than 2 L + 2 or than its padding from every impulse's response.
// interior[i]: row i is away from the ends.
void row_sums(const Filters& f, const double* t, int n, RowSums& sums,
              std::vector<char>& interior) {
  sums.resize(n);
  interior.assign(n, 0);
  std::vector<Difference> dif(n);
  for (int i = 0; i < n; ++i) dif[i] = difference(t, n, i);
  const int L = f.length;
  if (n < 2 * L + 2 || n - 1 < f.pad) return exact_sums(f, dif, n, sums);
  std::vector<double> reversed(n);
  for (int i = 0; i < n; ++i) reversed[i] = -t[n - 1 - i];
  for (int i = 0; i < n; ++i) {
    const bool left = i < L, right = i >= n - L;
    interior[i] = !left && !right;
    const Difference d = right ? difference(reversed.data(), n, n - 1 - i) : dif[i];
    for (int q = 0; q < 2; ++q) {
      const double* w = q == 0 ? d.first : d.second;
      for (int o = 0; o < 2; ++o) {
        double& out = o == 0 ? sums.w2[q][i] : sums.step2[q][i];
        if (o == 1 && !f.has_twice) continue;
        out = interior[i] ? interior_norm2(w, f.G[o]) : left_norm2(w, d, f.g[o], f.S[o], f.G[o]);
      }
    }
  }
}

// The filtered series at one cutoff (over each segment), and its residual sum of squares.
double filtered(const Butterworth2& f, const std::vector<double>& x, const Segments& segments,
                std::vector<double>& y, int pad) {
  y.resize(x.size());
  std::vector<double> scratch;
  double rss = 0;
  for (size_t s = 0; s < segments.begin.size(); ++s) {
    const int b = segments.begin[s], n = segments.end[s] - b;
    filtfilt(f, x.data() + b, n, y.data() + b, scratch, pad);
    for (int i = b; i < b + n; ++i) rss += (x[i] - y[i]) * (x[i] - y[i]);
  }
  return rss;
}

double residual(const std::vector<double>& x, const Segments& segments, double rate,
                double cutoff) {
  std::vector<double> y;
  const Butterworth2 f = butterworth_lowpass(cutoff / butterworth_correction(), rate);
  const double rss = filtered(f, x, segments, y, butterworth_padding(f));
  return std::sqrt(rss / static_cast<double>(x.size()));
}

// sigma^2 = RSS / sum(1 - 2 h_ii + |h_i|^2) of the filter at the highest cutoff (far from the
// ends: h_ii = g(0), |h_i|^2 = G(0)).
double noise_level(const std::vector<double>& x, const Segments& segments, double rate,
                   double highest) {
  const Butterworth2 f = butterworth_lowpass(highest / butterworth_correction(), rate);
  const int L = response_length(f);
  const std::vector<double> g = two_pass_response(f, L);
  const double per_sample = 1 - 2 * g[L] + autocorrelation(g).at[0];
  std::vector<double> y;
  const double rss = filtered(f, x, segments, y, butterworth_padding(f));
  const double dof = per_sample * static_cast<double>(x.size());
  return dof > 0 && std::isfinite(rss) ? std::sqrt(rss / dof) : 0.0;
}

// Series c of the m at x[r * ld + c]: estimates and error bars into out.
void estimate_series(const OfflineEstimator& e, const std::vector<double>& t,
                     const Segments& segments, double rate, const double* x, int ld, int m, int c,
                     AutoEstimate& out) {
  const int rows = static_cast<int>(t.size());
  std::vector<double> xs(rows);
  for (int r = 0; r < rows; ++r) xs[r] = x[static_cast<size_t>(r) * ld + c];
  const double top = butterworth_correction() * rate / 2, highest = kFitTo * top;
  double cutoff = e.cutoff;
  if (cutoff <= 0) {
    cutoff = residual_cutoff(xs, segments, rate).cutoff;
  } else if (cutoff >= top) {
    char text[160];
    std::snprintf(text, sizeof text,
                  ": the cutoff must be below %.4g Hz (0.802 x the Nyquist frequency of samples at "
                  "%.4g Hz)",
                  top, rate);
    throw std::invalid_argument(e.name + text);
  }
  out.cutoff[c] = cutoff;
  const double sigma = noise_level(xs, segments, rate, highest);
  out.noise[c] = sigma;
  const Filters f = make_filters(cutoff, rate);
  std::vector<double> y1, y2;
  filtered(f.fc, xs, segments, y1, f.pad);
  if (f.has_twice) filtered(f.twice, xs, segments, y2, f.pad);
  // Per segment: the estimates, the weights' sums; the steps' excess over the noise.
  std::vector<double> excess[2];
  double mean[2] = {}, counted = 0, mean_all[2] = {};  // over the rows away from the ends; all
  RowSums sums;
  std::vector<char> interior;
  // The filter takes the samples as evenly spaced; so do the differences: local row i at i / rate.
  std::vector<double> grid(rows);
  for (int i = 0; i < rows; ++i) grid[i] = i / rate;
  std::vector<double> w2[2];
  for (int q = 0; q < 2; ++q) excess[q].assign(rows, 0.0), w2[q].assign(rows, 0.0);
  for (size_t s = 0; s < segments.begin.size(); ++s) {
    const int b = segments.begin[s], n = segments.end[s] - b;
    const double* ts = grid.data();
    row_sums(f, ts, n, sums, interior);
    for (int i = 0; i < n; ++i) {
      const Difference d = difference(ts, n, i);
      const size_t at = static_cast<size_t>(b + i) * m + c;
      double v[2] = {}, step[2] = {};
      for (int k = 0; k < d.count; ++k) {
        const int r = b + d.row + k;
        v[0] += d.first[k] * y1[r], v[1] += d.second[k] * y1[r];
        if (f.has_twice)
          step[0] += d.first[k] * (y1[r] - y2[r]), step[1] += d.second[k] * (y1[r] - y2[r]);
      }
      out.first[at] = v[0], out.second[at] = v[1];
      out.valid[at] = std::min(d.count - 1, 2);
      for (int q = 0; q < 2; ++q) {
        w2[q][b + i] = sums.w2[q][i];
        excess[q][b + i] = step[q] * step[q] - sigma * sigma * sums.step2[q][i];
        mean_all[q] += excess[q][b + i];
        if (interior[i]) mean[q] += excess[q][b + i];
      }
      counted += interior[i];
    }
  }
  for (int q = 0; q < 2; ++q) {
    const double bias2 =
        std::max(0.0, counted > 0 ? mean[q] / counted : mean_all[q] / static_cast<double>(rows));
    std::vector<double>& se = q == 0 ? out.first_se : out.second_se;
    for (int r = 0; r < rows; ++r)
      se[static_cast<size_t>(r) * m + c] =
          std::sqrt(sigma * sigma * w2[q][r] + std::max(bias2, excess[q][r]));
  }
}

}  // namespace

double butterworth_correction(int passes) {
  return std::pow(std::pow(2.0, 1.0 / passes) - 1, 0.25);
}

Butterworth2 butterworth_lowpass(double cutoff, double rate) {
  if (!(cutoff > 0 && cutoff < rate / 2))
    throw std::invalid_argument("Butterworth low-pass: the cutoff " + std::to_string(cutoff) +
                                " Hz is not between 0 and half the rate " + std::to_string(rate) +
                                " Hz");
  // Winter's eq. 2.x with the pre-warped omega_c = tan(pi fc / fs): the bilinear transform.
  const double K = std::tan(M_PI * cutoff / rate), s2 = std::sqrt(2.0);
  const double norm = 1 / (1 + s2 * K + K * K);
  Butterworth2 f;
  f.b[0] = K * K * norm, f.b[1] = 2 * f.b[0], f.b[2] = f.b[0];
  f.a[0] = 1, f.a[1] = 2 * (K * K - 1) * norm, f.a[2] = (1 - s2 * K + K * K) * norm;
  // (I - A^T) zi = b[1:] - a[1:] b0 with A the companion matrix: the steady state of a unit step.
  const double B0 = f.b[1] - f.a[1] * f.b[0], B1 = f.b[2] - f.a[2] * f.b[0];
  f.zi[0] = (B0 + B1) / (1 + f.a[1] + f.a[2]);
  f.zi[1] = B1 - f.a[2] * f.zi[0];
  return f;
}

int butterworth_padding(const Butterworth2& f) { return std::max(kPad, response_length(f)); }

void filtfilt(const Butterworth2& f, const double* x, int n, double* y,
              std::vector<double>& scratch, int pad) {
  if (n <= 0) return;
  const int p = std::max(0, std::min(pad, n - 1)), N = n + 2 * p;
  scratch.resize(N);
  for (int k = 0; k < p; ++k) {
    scratch[k] = 2 * x[0] - x[p - k];                  // x[p], ..., x[1] reflected about x[0]
    scratch[p + n + k] = 2 * x[n - 1] - x[n - 2 - k];  // x[n-2], ... about x[n-1]
  }
  std::copy(x, x + n, scratch.begin() + p);
  pass(f, scratch.data(), N, false);
  pass(f, scratch.data(), N, true);
  std::copy(scratch.begin() + p, scratch.begin() + p + n, y);
}

ResidualChoice residual_cutoff(const std::vector<double>& x, const Segments& segments,
                               double rate) {
  ResidualChoice out;
  const double top = butterworth_correction() * rate / 2;
  out.lowest = kLowest * rate, out.highest = kFitTo * top;
  // The noise line: least squares R = a + b f over the high-frequency end.
  double sf = 0, sr = 0, sff = 0, sfr = 0;
  for (int k = 0; k < kFitPoints; ++k) {
    const double f = top * (kFitFrom + (kFitTo - kFitFrom) * k / (kFitPoints - 1));
    const double r = residual(x, segments, rate, f);
    sf += f, sr += r, sff += f * f, sfr += f * r;
  }
  const double n = kFitPoints, slope = (n * sfr - sf * sr) / (n * sff - sf * sf);
  out.intercept = (sr - slope * sf) / n;
  const double a = out.intercept;
  if (!(residual(x, segments, rate, out.highest) < a)) {  // no noise shows (or none to fit)
    out.cutoff = out.highest;
    return out;
  }
  if (residual(x, segments, rate, out.lowest) <= a) {
    out.cutoff = out.lowest;
    return out;
  }
  double lo = std::log(out.lowest), hi = std::log(out.highest);  // R(lo) > a >= R(hi)
  for (int k = 0; k < kBisections; ++k) {
    const double mid = (lo + hi) / 2;
    (residual(x, segments, rate, std::exp(mid)) > a ? lo : hi) = mid;
  }
  out.cutoff = std::exp(hi);
  return out;
}

void estimate_butterworth(const OfflineEstimator& e, const std::vector<double>& t, const double* x,
                          int ld, int m, double max_gap, AutoEstimate& out, int threads) {
  const int rows = static_cast<int>(t.size());
  const size_t size = static_cast<size_t>(rows) * m;
  out.series = m;
  out.first.assign(size, 0.0), out.second.assign(size, 0.0);
  out.first_se.assign(size, 0.0), out.second_se.assign(size, 0.0);
  out.valid.assign(size, 0);
  out.noise.assign(m, 0.0), out.cutoff.assign(m, 0.0), out.choice.assign(m, 0);
  if (rows < 2) return;
  const double dt = default_max_gap(t) / 5;
  if (!(dt > 0)) return;
  const Segments segments = find_segments(t, max_gap);
  const int workers = std::max(1, std::min(threads, m / kFilterSeriesPerThread));
  auto share = [&](int w) {
    for (int c = w; c < m; c += workers) estimate_series(e, t, segments, 1 / dt, x, ld, m, c, out);
  };
  if (workers == 1) return share(0);
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> errors(workers);
  for (int w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      try {
        share(w);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    });
  for (std::thread& p : pool) p.join();
  for (const std::exception_ptr& p : errors)
    if (p) std::rethrow_exception(p);
}

void butterworth_weight_norms(double cutoff, double rate, const std::vector<double>& t,
                              std::vector<double>& first, std::vector<double>& second) {
  RowSums sums;
  std::vector<char> interior;
  row_sums(make_filters(cutoff, rate), t.data(), static_cast<int>(t.size()), sums, interior);
  first = sums.w2[0], second = sums.w2[1];
}

void estimate_with_errors(const OfflineEstimator& e, const std::vector<double>& t, const double* x,
                          int ld, int m, double max_gap, AutoEstimate& out, int threads) {
  if (e.butterworth) return estimate_butterworth(e, t, x, ld, m, max_gap, out, threads);
  estimate_auto(t, x, ld, m, max_gap, out, threads);
}

}  // namespace mbk
