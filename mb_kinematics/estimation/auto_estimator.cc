#include "mb_kinematics/estimation/auto_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mbk {

namespace {

// A window is kept while the squared change of its estimates stays within this many times what
// the noise explains.
constexpr double kLepski = 2.0;
// At the ends, the window this many candidates shorter than the one chosen away from them.
constexpr int kEndStep = 1;

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

// Each series' noise level from the shortest window's residuals: sigma^2 = RSS / (n - tr H).
void noise_levels(const OfflineEstimator& e, const std::vector<double>& t, const Segments& segments,
                  const double* x, int ld, int m, std::vector<double>& sigma) {
  const int n = static_cast<int>(t.size());
  DerivativeWeights w;
  std::vector<double> rss(m, 0.0);
  double trace = 0;
  for (int i = 0; i < n; ++i) {
    derivative_weights(e, t, segments, i, w);
    if (w.valid < 2) {  // an unsmoothed sample: interpolated, h_ii = 1
      trace += 1;
      continue;
    }
    trace += w.value[(i - w.begin) / w.stride];
    for (int c = 0; c < m; ++c) {
      double fit = 0;
      for (int j = 0; j < w.count; ++j) fit += w.value[j] * x[w.row(j) * ld + c];
      const double r = x[i * ld + c] - fit;
      if (std::isfinite(r)) rss[c] += r * r;  // a bad sample spoils its fits, not the level
    }
  }
  sigma.assign(m, 0.0);
  for (int c = 0; c < m; ++c) sigma[c] = n - trace > 0.5 ? std::sqrt(rss[c] / (n - trace)) : 0;
}

// One window's derivative d of the active series: estimate[i * m + c], its noise-only standard
// error, and valid; tested[i]: both this window and the previous are centred on sample i (then
// change += |w_k,i - w_k-1,i|^2).
struct Pass {
  std::vector<double> estimate, se;
  std::vector<int> valid;
  std::vector<char> tested;
  std::vector<double> step2;  // |w_k,i - w_k-1,i|^2
  double change = 0, tested_count = 0;
};

void fit_window(const OfflineEstimator& e, const OfflineEstimator* previous,
                const std::vector<double>& t, const Segments& segments, const double* x, int ld,
                int m, int d, const std::vector<int>& active, const std::vector<double>& sigma,
                Pass& pass) {
  const int n = static_cast<int>(t.size());
  DerivativeWeights w, p;
  pass.change = pass.tested_count = 0;
  for (int i = 0; i < n; ++i) {
    derivative_weights(e, t, segments, i, w);
    pass.tested[i] = 0;
    if (previous) {
      derivative_weights(*previous, t, segments, i, p);
      pass.tested[i] =
          w.valid == 2 && p.valid == 2 && centred_window(t, i, w) && centred_window(t, i, p);
      pass.step2[i] = w.valid == 2 && p.valid == 2 ? difference2(w, p, d) : 0;
      if (pass.tested[i]) pass.change += pass.step2[i], pass.tested_count += 1;
    }
    const std::vector<double>& weights = weights_of(w, d);
    const double norm = std::sqrt(norm2(weights, w.count));
    for (int c : active) {
      const size_t at = static_cast<size_t>(i) * m + c;
      double sum = 0;
      for (int j = 0; j < w.count; ++j) sum += weights[j] * x[w.row(j) * ld + c];
      pass.estimate[at] = sum;
      pass.se[at] = sigma[c] * norm;
      pass.valid[at] = w.valid;
    }
  }
}

// Lepski's choice of derivative d per series over the samples away from the ends: the longest
// window before the first whose estimates moved more than the noise explains. Into `out`'s
// estimate, se (with the bias the last step showed) and valid; the choice per series.
void choose_windows(const std::vector<OfflineEstimator>& candidates, const std::vector<double>& t,
                    const Segments& segments, const double* x, int ld, int m, int d,
                    const std::vector<double>& sigma, Pass& out, std::vector<int>& choice) {
  const size_t n = t.size(), size = n * m;
  Pass cur;
  for (Pass* p : {&cur, &out}) {
    p->estimate.assign(size, 0.0), p->se.assign(size, 0.0), p->valid.assign(size, 0);
    p->tested.assign(n, 0), p->step2.assign(n, 0.0);
  }
  std::vector<int> active(m);
  for (int c = 0; c < m; ++c) active[c] = c;
  choice.assign(m, -1);
  for (size_t k = 0; k < candidates.size() && !active.empty(); ++k) {
    fit_window(candidates[k], k ? &candidates[k - 1] : nullptr, t, segments, x, ld, m, d, active,
               sigma, cur);
    std::vector<int> still;
    for (int c : active) {
      double moved = 0;  // sum_i (x_k,i - x_k-1,i)^2
      for (size_t i = 0; k > 0 && i < n; ++i) {
        const double step = cur.estimate[i * m + c] - out.estimate[i * m + c];
        if (cur.tested[i] && std::isfinite(step)) moved += step * step;
      }
      const double explained = sigma[c] * sigma[c] * cur.change;
      if (k > 0 && !(moved <= kLepski * explained)) continue;  // Lepski's test
      // The squared bias this step added beyond the noise, per sample, kept in the error bar:
      // the mean over the centred samples, or the sample's own where the window is shifted.
      const double bias2 = k > 0 ? std::max(0.0, moved - explained) / cur.tested_count : 0;
      for (size_t i = 0; i < n; ++i) {
        const size_t at = i * m + c;
        const double step = cur.estimate[at] - out.estimate[at];
        const double own =
            k > 0 && !cur.tested[i] ? step * step - sigma[c] * sigma[c] * cur.step2[i] : 0.0;
        out.estimate[at] = cur.estimate[at], out.valid[at] = cur.valid[at];
        out.se[at] = std::sqrt(cur.se[at] * cur.se[at] + std::max(bias2, own));
      }
      choice[c] = static_cast<int>(k);
      still.push_back(c);
    }
    active.swap(still);
  }
}

// Where the chosen window is shifted (an end, a gap), the accelerations of the window kEndStep
// candidates shorter: a one-sided fit's bias grows faster with its length.
void ends_step_down(const std::vector<OfflineEstimator>& candidates, const std::vector<double>& t,
                    const Segments& segments, const double* x, int ld, int m,
                    const std::vector<double>& sigma, const std::vector<int>& choice, Pass& pass) {
  DerivativeWeights w, shorter;
  for (int c = 0; c < m; ++c) {
    if (choice[c] < kEndStep) continue;
    for (size_t i = 0; i < t.size(); ++i) {
      derivative_weights(candidates[choice[c]], t, segments, static_cast<int>(i), w);
      if (w.valid < 2 || centred_window(t, static_cast<int>(i), w)) continue;
      derivative_weights(candidates[choice[c] - kEndStep], t, segments, static_cast<int>(i),
                         shorter);
      double sum = 0;
      for (int j = 0; j < shorter.count; ++j) sum += shorter.second[j] * x[shorter.row(j) * ld + c];
      const size_t at = i * m + c;
      pass.estimate[at] = sum;
      pass.se[at] =
          std::max(pass.se[at], sigma[c] * std::sqrt(norm2(shorter.second, shorter.count)));
    }
  }
}

}  // namespace

std::vector<OfflineEstimator> auto_candidates(const std::vector<double>& t) {
  const double dt = default_max_gap(t) / 5;  // the median interval
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

void estimate_auto(const std::vector<double>& t, const double* x, int ld, int m, double max_gap,
                   AutoEstimate& out) {
  const Segments segments = find_segments(t, max_gap);
  const std::vector<OfflineEstimator> candidates = auto_candidates(t);
  noise_levels(candidates.front(), t, segments, x, ld, m, out.noise);
  Pass velocity, acceleration;
  std::vector<int> velocity_choice;
  choose_windows(candidates, t, segments, x, ld, m, 1, out.noise, velocity, velocity_choice);
  choose_windows(candidates, t, segments, x, ld, m, 2, out.noise, acceleration, out.choice);
  out.series = m;
  out.first = std::move(velocity.estimate), out.first_se = std::move(velocity.se);
  ends_step_down(candidates, t, segments, x, ld, m, out.noise, out.choice, acceleration);
  out.second = std::move(acceleration.estimate), out.second_se = std::move(acceleration.se);
  out.valid.resize(acceleration.valid.size());
  for (size_t at = 0; at < out.valid.size(); ++at)
    out.valid[at] = std::min(velocity.valid[at], acceleration.valid[at]);
}

}  // namespace mbk
