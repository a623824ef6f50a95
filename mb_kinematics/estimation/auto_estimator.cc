#include "mb_kinematics/estimation/auto_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mb_kinematics/core/split_runs.h"

namespace mbk {

namespace {

// A window is kept while the squared change of its estimates stays within this many times what
// the noise explains.
constexpr double kLepski = 2.0;
// The same of the centred chain's long windows (auto_centred_candidates: 61 median intervals and
// more): stricter, so that the chosen window's bias stays where it grows as bias_growth says
// (further on, order 6's bias grows slower than L^6 and the bias taken from the next step would
// be too small: 87 % of the accelerations covered by the 2-sigma bars at 1 kHz and 1e-2 rad in
// test/estimation/auto_estimator_test.cc with kLepski).
constexpr double kCentredLepski = 1.5;
// At the ends and gaps, the accelerations' order at most.
constexpr int kEndOrder = 4;
// Away from them, the long windows' order (auto_centred_candidates).
constexpr int kCentredOrder = 6, kCentredTail = 2;
// The choice looks at every stride-th sample: n / kSelectionSamples, within [1, kMaxStride].
constexpr int kSelectionSamples = 1000, kMaxStride = 8;
// The estimating pass takes a thread more per this many samples at least, the choice pass per
// this many series (each of its threads computes every window's weights): fewer are not worth one.
constexpr size_t kRowsPerThread = 1024;
constexpr int kSeriesPerThread = 8;
// The choice pass with its selection samples shared out: a thread more per this many samples at
// least, and the samples' own sums kept for this many at a time.
constexpr size_t kSamplesPerThread = 16, kSamplesPerBatch = 256;

const std::vector<double>& weights_of(const DerivativeWeights& w, int d) {
  return d == 1 ? w.first : w.second;
}

double norm2(const std::vector<double>& v, int count) {
  double sum = 0;
  for (int j = 0; j < count; ++j) sum += v[j] * v[j];
  return sum;
}

// |a - b|^2 of two samples' weights of derivative d (rows may differ: strides).
double difference2(const DerivativeWeights& a, const DerivativeWeights& b, int d) {
  const std::vector<double>&av = weights_of(a, d), &bv = weights_of(b, d);
  double shared = 0;
  if (a.stride == 1 && b.stride == 1) {  // the same rows and sums as below, without the tests
    const int shift = b.begin - a.begin;
    for (int j = std::max(0, -shift); j < std::min(b.count, a.count - shift); ++j)
      shared += av[j + shift] * bv[j];
    return norm2(av, a.count) + norm2(bv, b.count) - 2 * shared;
  }
  for (int j = 0; j < b.count; ++j) {
    const int offset = b.row(j) - a.begin;
    if (offset < 0 || offset % a.stride != 0 || offset / a.stride >= a.count) continue;
    shared += av[offset / a.stride] * bv[j];
  }
  return norm2(av, a.count) + norm2(bv, b.count) - 2 * shared;
}

// Is sample i in the middle of the window (not shifted at an end or a gap)?
bool centred_window(const std::vector<double>& t, int i, const DerivativeWeights& w) {
  const double before = t[i] - t[w.begin], after = t[w.row(w.count - 1)] - t[i];
  return std::abs(before - after) <= 0.25 * (before + after);
}

// The series [begin, end) of a choice pass's share of them, and whether it also takes the sums
// every series shares (the trace, the weights' changes, the samples counted).
struct SeriesShare {
  int begin, end;
  bool shared;
};

// Selection sample i's share of each series' noise level from the shortest window's residuals,
// sigma^2 = RSS / (n - tr H): rss per series, the trace and the samples counted.
using Residuals = AutoChooser::Residuals;

void add_residuals(const OfflineEstimator& e, const std::vector<double>& t,
                   const Segments& segments, const double* x, int ld, int i, SeriesShare share,
                   DerivativeWeights& w, Residuals& res) {
  derivative_weights(e, t, segments, i, w);
  if (share.shared) res.count += 1;
  if (w.valid < 2) {  // an unsmoothed sample: interpolated, h_ii = 1
    if (share.shared) res.trace += 1;
    return;
  }
  if (share.shared) res.trace += w.value[(i - w.begin) / w.stride];
  for (int c = share.begin; c < share.end; ++c) {
    double fit = 0;
    for (int j = 0; j < w.count; ++j) fit += w.value[j] * x[w.row(j) * ld + c];
    const double r = x[i * ld + c] - fit;
    if (std::isfinite(r)) res.rss[c] += r * r;  // a bad sample spoils its fits, not the level
  }
}

std::vector<double> noise_levels(const Residuals& res) {
  std::vector<double> sigma(res.rss.size(), 0.0);
  for (size_t c = 0; c < sigma.size(); ++c)
    sigma[c] = res.count - res.trace > 0.5 ? std::sqrt(res.rss[c] / (res.count - res.trace)) : 0;
  return sigma;
}

// Lepski's statistics of both derivatives (d = 1, 2 at [d - 1]) over the selection samples:
// per candidate k >= 1, over the samples where both k and k - 1 are centred,
// moved[k * m + c] = sum_i (x_k,i - x_k-1,i)^2 (series c), change[k] = sum_i |w_k,i - w_k-1,i|^2
// and count[k] such samples.
using Statistics = AutoChooser::Statistics;

// A choice pass's scratch at a selection sample: two candidates' weights and estimates (candidate
// k's at [k % 2]), and those of the candidate the centred chain goes on from (`kept`).
struct LepskiScratch {
  DerivativeWeights w[2], kept_w;
  std::vector<double> estimate[2], kept_estimate;
  explicit LepskiScratch(int m)
      : estimate{std::vector<double>(2 * m), std::vector<double>(2 * m)} {}
};

// Selection sample i's share of Lepski's statistics of candidates `from` on (stats[d - 1] of
// derivative d, where not null): the scratch holds candidate from - 1's weights and estimates in
// `kept` (from > 0) or candidate 0's weights in w[0] (add_residuals'); candidate `keep`'s go
// there. Returns the candidates up to the first that is not valid and centred (longer ones are
// not either).
int add_lepski(const std::vector<OfflineEstimator>& candidates, const std::vector<double>& t,
               const Segments& segments, const double* x, int ld, int m, int i, SeriesShare share,
               LepskiScratch& scratch, Statistics* const (&stats)[2], int from, int keep) {
  const int kc = static_cast<int>(candidates.size());
  DerivativeWeights(&w)[2] = scratch.w;
  std::vector<double>(&estimate)[2] = scratch.estimate;
  if (from > 0)
    std::swap(w[(from - 1) % 2], scratch.kept_w),
        std::swap(estimate[(from - 1) % 2], scratch.kept_estimate);
  for (int k = from; k < kc; ++k) {
    DerivativeWeights &cur = w[k % 2], &prev = w[(k + 1) % 2];
    if (k > 0) derivative_weights(candidates[k], t, segments, i, cur);
    if (cur.valid < 2 || !centred_window(t, i, cur)) return k;
    std::vector<double>&now = estimate[k % 2], &before = estimate[(k + 1) % 2];
    // Both derivatives of the share's series, each the sum over the window's rows in order.
    apply_weights(cur, x + share.begin, ld, share.end - share.begin, now.data() + share.begin,
                  now.data() + m + share.begin);
    if (k == keep) scratch.kept_w = cur, scratch.kept_estimate = now;
    for (int d = 1; d <= 2; ++d) {
      if (k == 0 || !stats[d - 1]) continue;
      Statistics& s = *stats[d - 1];
      if (share.shared) s.change[k] += difference2(cur, prev, d), s.count[k] += 1;
      for (int c = share.begin; c < share.end; ++c) {
        const double step = now[(d - 1) * m + c] - before[(d - 1) * m + c];
        if (std::isfinite(step)) s.moved[k * m + c] += step * step;
      }
    }
  }
  return kc;
}

// Selection sample i's share of the first chain's statistics (both derivatives), then of the
// centred chain's after the `shared` windows both begin with (the same weights, estimates and
// statistics: its accelerations' are the first chain's there, AutoChooser::choice), from the last
// shared one on; of the centred chain, the accelerations' alone (its velocities' are not used).
void add_sample(const std::vector<OfflineEstimator>& candidates,
                const std::vector<OfflineEstimator>& centred_candidates, size_t shared,
                const std::vector<double>& t, const Segments& segments, const double* x, int ld,
                int m, int i, SeriesShare share, LepskiScratch& scratch, Statistics (&stats)[2],
                Statistics& centred) {
  const int keep = static_cast<int>(shared) - 1;
  const int reached = add_lepski(candidates, t, segments, x, ld, m, i, share, scratch,
                                 {&stats[0], &stats[1]}, 0, keep);
  if (shared == 0) derivative_weights(centred_candidates.front(), t, segments, i, scratch.w[0]);
  if (shared == 0 || reached > keep)
    add_lepski(centred_candidates, t, segments, x, ld, m, i, share, scratch, {nullptr, &centred},
               static_cast<int>(shared), -1);
}

// Lepski's choice per series: the longest window before the first whose estimates moved more
// than the noise explains, sum_i (x_k,i - x_k-1,i)^2 <= kLepski sigma^2 sum_i |w_k,i - w_k-1,i|^2;
// bias2: the squared bias per sample its last step showed beyond the noise (for the error bar).
// centred: the centred chain's candidates, whose long windows (of another degree than the first
// ones) take kCentredLepski.
void choose(const Statistics& s, const std::vector<double>& sigma, std::vector<int>& choice,
            std::vector<double>& bias2, const std::vector<OfflineEstimator>* centred = nullptr) {
  const int m = static_cast<int>(sigma.size()), kc = static_cast<int>(s.change.size());
  choice.assign(m, 0), bias2.assign(m, 0.0);
  for (int c = 0; c < m; ++c)
    for (int k = 1; k < kc; ++k) {
      const double moved = s.moved[k * m + c], explained = sigma[c] * sigma[c] * s.change[k];
      const bool strict = centred && (*centred)[k].order != centred->front().order;
      const double lepski = strict ? kCentredLepski : kLepski;
      if (!(moved <= lepski * explained)) break;  // Lepski's test
      choice[c] = k;
      bias2[c] = s.count[k] > 0 ? std::max(0.0, moved - explained) / s.count[k] : 0.0;
    }
}

// Lepski's choice of the accelerations among the centred windows (choose's) and, where the
// chosen window k and the next, k + 1, have one degree, k's squared bias per sample from that
// step, the first it failed: its bias is b_k+1 - b_k = b_k bias_growth(k), so
//   b_k^2 = (sum_i (x_k+1,i - x_k,i)^2 - sigma^2 sum_i |w_k+1,i - w_k,i|^2) / count / growth^2
// (the mean: where the next window is not centred; each sample takes its own step,
// centred_accelerations). The steps accepted before k mostly measure noise: the shorter
// window's weights are the larger (|w''|^2 grows as L^-5), so their excess beyond the noise
// overstates k's bias several times over (the 2-sigma bars of
// test/estimation/auto_estimator_test.cc would cover 99 % of the accelerations).
void choose_centred(const Statistics& s, const std::vector<double>& sigma,
                    const std::vector<OfflineEstimator>& candidates, std::vector<int>& choice,
                    std::vector<double>& bias2) {
  choose(s, sigma, choice, bias2, &candidates);
  const int m = static_cast<int>(sigma.size());
  for (int c = 0; c < m; ++c) {
    const int k = choice[c];
    const double growth = bias_growth(candidates, k);
    if (!(growth > 0) || s.count[k + 1] <= 0) continue;
    const double moved = s.moved[(k + 1) * m + c],
                 explained = sigma[c] * sigma[c] * s.change[k + 1];
    bias2[c] = std::max(0.0, moved - explained) / s.count[k + 1] / (growth * growth);
  }
}

// Every series' estimates of both derivatives at a sample from an AutoSampleWeights' windows (each
// the sum over the window's rows in order, apply_weights): [d - 1] per derivative d, of w, of
// shorter where the AutoSampleWeights has it, of end where it is shifted.
struct SampleEstimates {
  std::vector<double> w[2], shorter[2], end[2];
  explicit SampleEstimates(int m) {
    for (auto* v : {&w, &shorter, &end}) (*v)[0].resize(m), (*v)[1].resize(m);
  }
  void load(const AutoSampleWeights& s, const double* x, int ld) {
    const int m = static_cast<int>(w[0].size());
    apply_weights(s.w, x, ld, m, w[0].data(), w[1].data());
    if (s.has_shorter) apply_weights(s.shorter, x, ld, m, shorter[0].data(), shorter[1].data());
    if (s.shifted) apply_weights(s.end, x, ld, m, end[0].data(), end[1].data());
  }
};

// Series c's estimate of its chosen derivative at a sample and its standard error: noise and
// the squared bias the choice's last step showed (its mean over the samples, or where larger
// the step from the shorter window at this sample beyond the noise: the bias is not uniform);
// where the window is shifted, the accelerations from the shorter window at order kEndOrder at
// most (a one-sided fit's bias and variance grow faster with its length and order).
void final_estimate(const AutoSampleWeights& s, const SampleEstimates& e, int c, double sigma,
                    int d, double bias2, double& estimate, double& se) {
  estimate = e.w[d - 1][c];
  se = std::sqrt(sigma * sigma * s.norm2_w[d - 1] + bias2);
  if (!s.has_shorter) return;
  const double step = estimate - e.shorter[d - 1][c];
  const double own = step * step - sigma * sigma * s.step2[d - 1];
  se = std::sqrt(se * se + std::max(0.0, own - bias2));
  if (!s.shifted || d == 1) return;
  estimate = e.end[1][c];
  se = std::max(se, sigma * s.end_norm);
}

// Sample i's accelerations where the window of the centred choice (centred_in_use: its indices)
// and the next one are centred, in place of final_rows' (the weights of each such window once):
// the standard error from the noise and the bias the sample's own step to the next window shows
// beyond the noise, divided by bias_growth (choose_centred); where the chosen window is the
// chain's last of its degree, the mean bias of its last accepted step.
void centred_accelerations(const AutoChoice& chosen, const std::vector<int>& centred_in_use,
                           const std::vector<double>& t, const Segments& segments, const double* x,
                           int ld, int m, int i, AutoSampleWeights& w, SampleEstimates& estimates,
                           AutoEstimate& out) {
  for (const int k : centred_in_use) {
    if (k < 0) continue;  // series of the first chain alone
    w.load_centred(chosen.centred_candidates, t, segments, i, k);
    if (!w.centred) continue;
    apply_weights(w.w, x, ld, m, estimates.w[0].data(), estimates.w[1].data());
    if (w.has_longer)  // the next window's estimates, in the `shorter` scratch
      apply_weights(w.longer, x, ld, m, estimates.shorter[0].data(), estimates.shorter[1].data());
    for (int c = 0; c < m; ++c) {
      if (chosen.centred_choice[c] != k) continue;
      const size_t at = static_cast<size_t>(i) * m + c;
      const double sigma = chosen.noise[c], estimate = estimates.w[1][c];
      double bias2 = chosen.centred_bias2[c];
      if (w.has_longer) {
        const double step = estimates.shorter[1][c] - estimate;
        bias2 = std::max(0.0, step * step - sigma * sigma * w.step2_longer) / (w.growth * w.growth);
      }
      out.second[at] = estimate;
      out.second_se[at] = std::sqrt(sigma * sigma * w.norm2_w[1] + bias2);
    }
  }
}

// Samples [begin, end)'s estimates of both derivatives with the chosen windows (in_use,
// centred_in_use: their indices): the weights of each window in use once per sample, for every
// series that uses it.
void final_rows(const AutoChoice& chosen, const std::vector<int>& in_use,
                const std::vector<int>& centred_in_use, const std::vector<double>& t,
                const Segments& segments, const double* x, int ld, int m, size_t begin, size_t end,
                AutoEstimate& out) {
  const std::vector<int>(&choice)[2] = chosen.choice;
  AutoSampleWeights both[2];  // this window's, and the one before in in_use (ascending)
  SampleEstimates estimates(m);
  for (size_t i = begin; i < end; ++i) {
    for (size_t u = 0; u < in_use.size(); ++u) {
      const int k = in_use[u];
      AutoSampleWeights &w = both[u % 2], &before = both[(u + 1) % 2];
      const bool known = u > 0 && in_use[u - 1] == k - 1;  // before.w: candidate k - 1's, at i
      w.load(chosen.candidates, t, segments, static_cast<int>(i), k, known ? &before.w : nullptr);
      estimates.load(w, x, ld);
      for (int c = 0; c < m; ++c) {
        const size_t at = i * m + c;
        if (choice[0][c] != k && choice[1][c] != k) continue;
        out.valid[at] = std::min(out.valid[at], w.w.valid);
        const double sigma = chosen.noise[c];
        if (choice[0][c] == k)
          final_estimate(w, estimates, c, sigma, 1, chosen.bias2[0][c], out.first[at],
                         out.first_se[at]);
        if (choice[1][c] == k)
          final_estimate(w, estimates, c, sigma, 2, chosen.bias2[1][c], out.second[at],
                         out.second_se[at]);
      }
    }
    centred_accelerations(chosen, centred_in_use, t, segments, x, ld, m, static_cast<int>(i),
                          both[0], estimates, out);
  }
}

// Every sample's estimates (final_rows), the samples shared out in runs among `threads` threads:
// each sample's own sums, the same bits on any count.
void final_pass(const AutoChoice& chosen, const std::vector<double>& t, const Segments& segments,
                const double* x, int ld, int m, int threads, AutoEstimate& out) {
  const size_t n = t.size(), size = n * m;
  out.first.assign(size, 0.0), out.second.assign(size, 0.0);
  out.first_se.assign(size, 0.0), out.second_se.assign(size, 0.0), out.valid.assign(size, 2);
  auto distinct = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  };
  std::vector<int> in_use = chosen.choice[0];
  in_use.insert(in_use.end(), chosen.choice[1].begin(), chosen.choice[1].end());
  in_use = distinct(in_use);
  const std::vector<int> centred_in_use = distinct(chosen.centred_choice);
  const size_t runs = std::clamp<size_t>(threads, 1, std::max<size_t>(1, n / kRowsPerThread));
  split_runs(n, static_cast<int>(runs), [&](size_t, size_t begin, size_t end) {
    final_rows(chosen, in_use, centred_in_use, t, segments, x, ld, m, begin, end, out);
  });
}

}  // namespace

void AutoSampleWeights::load(const std::vector<OfflineEstimator>& candidates,
                             const std::vector<double>& t, const Segments& segments, int i, int k,
                             const DerivativeWeights* known) {
  derivative_weights(candidates[k], t, segments, i, w);
  for (int d = 1; d <= 2; ++d) norm2_w[d - 1] = norm2(weights_of(w, d), w.count);
  centred = w.valid == 2 && centred_window(t, i, w);
  shifted = k > 0 && w.valid == 2 && !centred;
  has_shorter = k > 0 && w.valid == 2;
  if (!has_shorter) return;
  if (known)
    shorter = *known;  // the same weights as computing them again
  else
    derivative_weights(candidates[k - 1], t, segments, i, shorter);
  for (int d = 1; d <= 2; ++d) step2[d - 1] = difference2(w, shorter, d);
  if (!shifted) return;
  OfflineEstimator e = candidates[k - 1];
  e.order = std::min(e.order, kEndOrder);
  derivative_weights(e, t, segments, i, end);
  end_norm = std::sqrt(norm2(end.second, end.count));
}

void AutoSampleWeights::load_centred(const std::vector<OfflineEstimator>& candidates,
                                     const std::vector<double>& t, const Segments& segments, int i,
                                     int k) {
  derivative_weights(candidates[k], t, segments, i, w);
  norm2_w[1] = norm2(w.second, w.count);
  centred = w.valid == 2 && centred_window(t, i, w);
  shifted = has_shorter = false;
  growth = bias_growth(candidates, k);
  has_longer = false;
  if (centred && growth > 0) {
    derivative_weights(candidates[k + 1], t, segments, i, longer);
    has_longer = longer.valid == 2 && centred_window(t, i, longer);
    if (has_longer) step2_longer = difference2(w, longer, 2);
  }
  centred = has_longer;
}

double bias_growth(const std::vector<OfflineEstimator>& candidates, int k) {
  if (k + 1 >= static_cast<int>(candidates.size())) return 0;
  const OfflineEstimator &e = candidates[k], &next = candidates[k + 1];
  if (next.order != e.order || !(e.window_seconds > 0)) return 0;
  const int power = 2 * ((e.order - 2) / 2) + 2;
  return std::pow(next.window_seconds / e.window_seconds, power) - 1;
}

std::vector<OfflineEstimator> auto_candidates(const std::vector<double>& t) {
  return auto_candidates(default_max_gap(t) / 5);  // the median interval
}

std::vector<OfflineEstimator> auto_centred_candidates(double dt) {
  const std::vector<OfflineEstimator> plain = auto_candidates(dt);
  std::vector<OfflineEstimator> out = plain;
  for (OfflineEstimator& e : out) {
    if (e.order != 4) continue;
    e.order = kCentredOrder;
    char name[48];
    std::snprintf(name, sizeof name, "centered_%gs_%d", e.window_seconds, e.order);
    e.name = name;
  }
  // Then the longest at order 4 again: less noise than the longest at order 6 (at most
  // kMaxOfflineWindow samples fitted), for slow motion.
  out.insert(out.end(), plain.end() - kCentredTail, plain.end());
  return out;
}

std::vector<OfflineEstimator> auto_candidates(double dt) {
  std::vector<OfflineEstimator> out;
  for (int samples : {7, 11, 15, 21, 31, 41, 61, 81, 121, 161, 241, 321, 481, 641}) {
    OfflineEstimator e;
    e.order = samples <= kMaxOfflineWindow ? 5 : 4;
    if (dt > 0)
      e.window_seconds = samples * dt;
    else
      e.window_samples = 7;
    char name[48];
    std::snprintf(name, sizeof name, "centered_%gs_%d", e.window_seconds, e.order);
    e.name = name;
    out.push_back(e);
  }
  return out;
}

// Do both estimators fit the same window (the same weights at every sample)?
bool same_window(const OfflineEstimator& a, const OfflineEstimator& b) {
  return a.order == b.order && a.window_seconds == b.window_seconds &&
         a.window_samples == b.window_samples;
}

// A choice pass's sums (AutoChooser's Residuals and Statistics): the whole recording's, or one
// selection sample's terms alone.
struct AutoChooser::Sums {
  Residuals residuals;
  Statistics stats[2], centred;
  explicit Sums(const AutoChooser& c)
      : residuals{std::vector<double>(c.m_, 0.0)},
        stats{c.stats_[0], c.stats_[1]},
        centred(c.centred_stats_) {
    clear();
  }
  void clear() {
    std::fill(residuals.rss.begin(), residuals.rss.end(), 0.0);
    residuals.trace = residuals.count = 0;
    for (Statistics* s : {&stats[0], &stats[1], &centred})
      for (std::vector<double>* v : {&s->moved, &s->change, &s->count})
        std::fill(v->begin(), v->end(), 0.0);
  }
};

namespace {

void add_to(const std::vector<double>& terms, std::vector<double>& sums) {
  for (size_t j = 0; j < terms.size(); ++j) sums[j] += terms[j];
}

void add_to(const AutoChooser::Statistics& terms, AutoChooser::Statistics& sums) {
  add_to(terms.moved, sums.moved), add_to(terms.change, sums.change);
  add_to(terms.count, sums.count);
}

}  // namespace

AutoChooser::AutoChooser(double median_interval, long rows, int m, int threads)
    : candidates_(auto_candidates(median_interval)),
      centred_(auto_centred_candidates(median_interval)),
      stride_(static_cast<int>(std::clamp(rows / kSelectionSamples, 1L, long{kMaxStride}))),
      m_(m),
      threads_(std::clamp(threads, 1, std::max(1, m / kSeriesPerThread))),
      sample_threads_(threads_ < threads ? threads : 1),
      residuals_{std::vector<double>(m, 0.0)} {
  for (Statistics* s : {&stats_[0], &stats_[1], &centred_stats_}) {
    const size_t kc = (s == &centred_stats_ ? centred_ : candidates_).size();
    s->moved.assign(kc * m, 0.0), s->change.assign(kc, 0.0), s->count.assign(kc, 0.0);
  }
  while (shared_ < std::min(candidates_.size(), centred_.size()) &&
         same_window(candidates_[shared_], centred_[shared_]))
    ++shared_;
}

OfflineReach AutoChooser::reach() const {
  OfflineReach reach, one;
  for (const std::vector<OfflineEstimator>* chain : {&candidates_, &centred_})
    for (const OfflineEstimator& e : *chain) {
      offline_reach(e, one);
      reach.seconds = std::max(reach.seconds, one.seconds);
      reach.samples = std::max(reach.samples, one.samples);
    }
  return reach;
}

void AutoChooser::add(const std::vector<double>& t, const Segments& segments, const double* x,
                      int ld, long first, int from, int to) {
  if (sample_threads_ > 1) return add_by_samples(t, segments, x, ld, first, from, to);
  // Each part: its series, every selection sample.
  split_runs(m_, threads_, [&](size_t part, size_t begin, size_t end) {
    const SeriesShare share{static_cast<int>(begin), static_cast<int>(end), part == 0};
    LepskiScratch scratch(m_);
    for (int i = from; i < to; ++i) {
      if ((first + i) % stride_ != 0) continue;
      add_residuals(candidates_.front(), t, segments, x, ld, i, share, scratch.w[0], residuals_);
      add_sample(candidates_, centred_, shared_, t, segments, x, ld, m_, i, share, scratch, stats_,
                 centred_stats_);
    }
  });
}

// Each part: its selection samples, every series; each sample's terms summed apart (Sums, from
// zero), then added to the sums in the samples' order. The same bits as add's: each sum takes
// the same terms in the same order (0 + v is v; and a sum from +0 of these terms is never -0,
// so the zeros of a term a sample does not have change nothing).
void AutoChooser::add_by_samples(const std::vector<double>& t, const Segments& segments,
                                 const double* x, int ld, long first, int from, int to) {
  std::vector<int> selected;
  for (int i = from; i < to; ++i)
    if ((first + i) % stride_ == 0) selected.push_back(i);
  std::vector<Sums> terms(std::min(selected.size(), kSamplesPerBatch), Sums(*this));
  const SeriesShare all{0, m_, true};
  for (size_t b = 0; b < selected.size(); b += kSamplesPerBatch) {
    const size_t n = std::min(kSamplesPerBatch, selected.size() - b);
    const size_t runs =
        std::clamp<size_t>(sample_threads_, 1, std::max<size_t>(1, n / kSamplesPerThread));
    split_runs(n, static_cast<int>(runs), [&](size_t, size_t begin, size_t end) {
      LepskiScratch scratch(m_);
      for (size_t j = begin; j < end; ++j) {
        Sums& s = terms[j];
        const int i = selected[b + j];
        s.clear();
        add_residuals(candidates_.front(), t, segments, x, ld, i, all, scratch.w[0], s.residuals);
        add_sample(candidates_, centred_, shared_, t, segments, x, ld, m_, i, all, scratch, s.stats,
                   s.centred);
      }
    });
    for (size_t j = 0; j < n; ++j) {
      const Sums& s = terms[j];
      add_to(s.residuals.rss, residuals_.rss);
      residuals_.trace += s.residuals.trace, residuals_.count += s.residuals.count;
      add_to(s.stats[0], stats_[0]), add_to(s.stats[1], stats_[1]);
      add_to(s.centred, centred_stats_);
    }
  }
}

AutoChoice AutoChooser::choice() const {
  AutoChoice out;
  out.candidates = candidates_;
  out.noise = noise_levels(residuals_);
  for (int d = 1; d <= 2; ++d)
    choose(stats_[d - 1], out.noise, out.choice[d - 1], out.bias2[d - 1]);
  out.centred_candidates = centred_;
  Statistics centred = centred_stats_;  // the shared windows' are the first chain's (add_sample)
  for (size_t k = 1; k < shared_; ++k) {
    centred.change[k] = stats_[1].change[k], centred.count[k] = stats_[1].count[k];
    for (int c = 0; c < m_; ++c) centred.moved[k * m_ + c] = stats_[1].moved[k * m_ + c];
  }
  choose_centred(centred, out.noise, centred_, out.centred_choice, out.centred_bias2);
  return out;
}

OfflineReach AutoChoice::reach() const {
  OfflineReach out, one;
  auto add = [&](const OfflineEstimator& e) {
    offline_reach(e, one);
    out.seconds = std::max(out.seconds, one.seconds);
    out.samples = std::max(out.samples, one.samples);
  };
  for (const std::vector<int>& c : choice)
    for (int v : c) add(candidates[v]);
  for (int v : centred_choice) {
    if (v < 0) continue;
    add(centred_candidates[v]);
    // The next window, whose step gives the bias (centred_accelerations).
    if (bias_growth(centred_candidates, v) > 0) add(centred_candidates[v + 1]);
  }
  return out;
}

void estimate_chosen(const AutoChoice& choice, const std::vector<double>& t,
                     const Segments& segments, const double* x, int ld, AutoEstimate& out,
                     int threads) {
  const int m = static_cast<int>(choice.noise.size());
  out.series = m;
  out.noise = choice.noise;
  out.choice = choice.choice[1];
  final_pass(choice, t, segments, x, ld, m, threads, out);
}

void estimate_auto(const std::vector<double>& t, const double* x, int ld, int m, double max_gap,
                   AutoEstimate& out, int threads) {
  AutoChooser chooser(default_max_gap(t) / 5, static_cast<long>(t.size()), m, threads);
  const Segments segments = find_segments(t, max_gap);
  chooser.add(t, segments, x, ld, 0, 0, static_cast<int>(t.size()));
  estimate_chosen(chooser.choice(), t, segments, x, ld, out, threads);
}

}  // namespace mbk
