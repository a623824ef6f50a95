#include "mb_kinematics/estimation/offline_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/butterworth_estimator.h"

namespace mbk {
namespace {

// The fits' order at most (auto's centred long windows, auto_estimator.h); --estimator's.
constexpr int kMaxOrder = 6, kMaxNamedOrder = 5;
constexpr double kDoubleEpsilon = std::numeric_limits<double>::epsilon();

// std::lower_bound(t + from, t + i, x) (ahead: false; the first stamp not before x) or
// std::upper_bound(t + i, t + to, x) (ahead: true; the first stamp after x), found by steps that
// double from i: a window's edge lies a window's length from i, not the segment's.
int search_from(const std::vector<double>& t, int i, int bound, double x, bool ahead) {
  const auto beyond = [&](int k) { return ahead ? x < t[k] : t[k] < x; };
  int near = i, step = 1;  // the edge lies between near and far (far exclusive when ahead)
  for (;;) {
    const int far = ahead ? std::min(bound, i + step) : std::max(bound, i - step);
    if (far == bound || beyond(far)) {
      const auto first = t.begin() + (ahead ? near : far), last = t.begin() + (ahead ? far : near);
      return static_cast<int>(
          (ahead ? std::upper_bound(first, last, x) : std::lower_bound(first, last, x)) -
          t.begin());
    }
    near = far, step *= 2;
  }
}

// The window [begin, end) for sample i inside segment [sb, se): centred where it can be,
// shifted to one side near the segment's ends.
void window_range(const OfflineEstimator& e, const std::vector<double>& t, int sb, int se, int i,
                  int& begin, int& end) {
  if (e.window_samples > 0) {
    const int n = std::min(e.window_samples, se - sb);
    begin = std::clamp(i - e.window_samples / 2, sb, se - n);
    end = begin + n;
    return;
  }
  const double half = e.window_seconds / 2 * (1 + 1e-9);  // stamps on the edge are in
  double lo = t[i] - half, hi = t[i] + half;
  if (lo < t[sb]) hi += t[sb] - lo, lo = t[sb];              // one-sided at the start
  if (hi > t[se - 1]) lo -= hi - t[se - 1], hi = t[se - 1];  // and at the end
  begin = search_from(t, i, sb, lo, false);
  end = search_from(t, i, se, hi, true);
  // Sparse samples: widen to order + 3 samples (nearest first) so the fit still smooths.
  while (end - begin < e.order + 3 && (begin > sb || end < se)) {
    if (begin > sb && (end >= se || t[i] - t[begin - 1] <= t[end] - t[i]))
      --begin;
    else
      ++end;
  }
}

}  // namespace

const std::vector<std::string>& offline_estimator_names() {
  static const std::vector<std::string> names = {"auto",
                                                 "centered_0.4s_4",
                                                 "centered_0.1s_4",
                                                 "centered_0.2s_4",
                                                 "centered_0.3s_4",
                                                 "centered_0.4s_5",
                                                 "centered_9_4",
                                                 "centered_15_3"};
  return names;
}

const char* default_offline_estimator() { return offline_estimator_names().front().c_str(); }

OfflineEstimator make_offline_estimator(const std::string& name) {
  OfflineEstimator e;
  e.name = name;
  int used = 0, samples = 0, order = 0;
  double seconds = 0;
  if (name == "auto") {
    e.automatic = true;
    return e;
  }
  if (name.rfind("butterworth:", 0) == 0) {
    e.butterworth = true;
    if (name == "butterworth:auto") return e;
    if (std::sscanf(name.c_str(), "butterworth:%lf%n", &e.cutoff, &used) == 1 &&
        used == static_cast<int>(name.size()) && std::isfinite(e.cutoff) && e.cutoff > 0)
      return e;
    throw std::invalid_argument("offline estimator '" + name +
                                "': need butterworth:<cutoff in Hz > 0>, e.g. butterworth:6, or "
                                "butterworth:auto");
  }
  if (std::sscanf(name.c_str(), "centered_%lfs_%d%n", &seconds, &order, &used) == 2 &&
      used == static_cast<int>(name.size())) {
    e.window_seconds = seconds;
  } else if (std::sscanf(name.c_str(), "centered_%d_%d%n", &samples, &order, &used) == 2 &&
             used == static_cast<int>(name.size())) {
    e.window_samples = samples;
  } else {
    throw std::invalid_argument(
        "unknown offline estimator '" + name +
        "' (known: auto, centered_<samples>_<order>, e.g. centered_9_4, "
        "centered_<seconds>s_<order>, e.g. centered_0.1s_3, "
        "butterworth:<cutoff Hz>, e.g. butterworth:6, or butterworth:auto)");
  }
  e.order = order;
  const bool window_ok = e.window_seconds != 0
                             ? std::isfinite(seconds) && seconds > 0
                             : samples % 2 == 1 && samples > order && samples <= kMaxOfflineWindow;
  if (order < 2 || order > kMaxNamedOrder || !window_ok)
    throw std::invalid_argument("offline estimator '" + name +
                                "': need 2 <= order <= 5 and an odd sample window above the "
                                "order (at most 41) or a positive time window");
  return e;
}

// window_range: a time window reaches half its span each side, twice that when shifted to one
// side, then widens by up to order + 3 samples; a sample window reaches its own length each side
// at most (shifted at an end).
bool offline_reach(const OfflineEstimator& e, OfflineReach& reach) {
  if (e.whole_series()) return false;
  if (e.window_samples > 0)
    reach = {0.0, e.window_samples};
  else
    reach = {e.window_seconds * (1 + 1e-6), e.order + 4};
  return true;
}

Segments find_segments(const std::vector<double>& t, double max_gap, double period) {
  Segments s;
  s.period = period;
  s.segment_of.resize(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    if (i == 0 || (max_gap > 0 && t[i] - t[i - 1] > max_gap)) {
      if (i > 0) s.end.push_back(static_cast<int>(i));
      s.begin.push_back(static_cast<int>(i));
    }
    s.segment_of[i] = static_cast<int>(s.begin.size()) - 1;
  }
  if (!t.empty()) s.end.push_back(static_cast<int>(t.size()));
  return s;
}

double default_max_gap(const std::vector<double>& t) {
  if (t.size() < 2) return 0;
  std::vector<double> dt(t.size() - 1);
  for (size_t i = 1; i < t.size(); ++i) dt[i - 1] = t[i] - t[i - 1];
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return 5 * dt[dt.size() / 2];
}

// Least squares in s = (t_j - t_i) / scale: c = N^-1 A^T x with A_jc = s_j^c and the normal
// matrix N = A^T A, N_ab = sum_j s_j^(a + b); x'(t_i) = c1 / scale, x''(t_i) = 2 c2 / scale^2, so
// the weights are A N^-1 e1 / scale and 2 A N^-1 e2 / scale^2 (and the fitted value's A N^-1 e0). N
// is solved by Cholesky in fixed arrays (order <= 6): no allocation, no general-size Eigen solver.
namespace {

// Row j's weights from s_j (in w.first[j]) and g[m] = N^-1 e_m (derivative_weights): value =
// sum_c s_j^c g[0][c], first and second likewise, scaled. Two rows at a time as packs of two
// doubles (GNU vectors, SSE2) that multiply and add lane by lane: each row's products and sums in
// the same order as one row alone, so the same bits.
template <typename T, typename G>
inline void weight_row_pack(T s, int order, double scale, const G& g, T& value, T& first,
                            T& second) {
  T p = T{} + 1;  // T{}: +0 in every lane
  value = first = second = T{};
  for (int c = 0; c <= order; ++c, p *= s)
    value += p * g[0][c], first += p * g[1][c], second += p * g[2][c];
  first = first / scale;
  second = order >= 2 ? 2.0 * second / (scale * scale) : T{};
}

void weight_rows(int n, int order, double scale, const double (&g)[3][kMaxOrder + 1],
                 DerivativeWeights& w) {
  typedef double Pack __attribute__((vector_size(2 * sizeof(double))));
  int j = 0;
  for (; j + 2 <= n; j += 2) {
    Pack s, value, first, second;
    std::memcpy(&s, &w.first[j], sizeof s);
    weight_row_pack(s, order, scale, g, value, first, second);
    std::memcpy(&w.value[j], &value, sizeof value);
    std::memcpy(&w.first[j], &first, sizeof first);
    std::memcpy(&w.second[j], &second, sizeof second);
  }
  for (; j < n; ++j)
    weight_row_pack(w.first[j], order, scale, g, w.value[j], w.first[j], w.second[j]);
}

// x rounded to the nearest whole number (ties to even), inline; for |x| < 2^51. T: a double, or a
// pack of doubles (GNU vectors) rounded lane by lane with the same bits.
template <typename T>
inline T nearest_whole(T x) {
  constexpr double kShift = 6755399441055744.0;  // 1.5 x 2^52: the sum keeps no fraction
  return (x + kShift) - kShift;
}

// The window's time offsets d_j = t_row(j) - t_i (seconds; doc/recorded_data.md, "Offline
// estimators"). Stamps on a grid of `period` (each within the grid's tolerance of its grid time,
// far below a period): whole periods. Stamps that are whole nanoseconds (a bag's, a CSV's of at
// most 9 decimals) are doubles within a few units of their last place of them, so their
// differences lie within `tolerance` of whole nanoseconds: taken as those, exactly. Else the
// doubles' differences.
void window_offsets(const std::vector<double>& t, int i, const DerivativeWeights& w, double period,
                    double* d) {
  const int n = w.count;
  if (period > 0 && (t[w.row(n - 1)] - t[w.begin]) / period < 0x1p50) {
    typedef double Pack __attribute__((vector_size(2 * sizeof(double))));
    int j = 0;
    for (; j + 2 <= n; j += 2) {
      const Pack offset = Pack{t[w.row(j)], t[w.row(j + 1)]} - t[i];
      const Pack whole = nearest_whole(offset / period) * period;
      std::memcpy(&d[j], &whole, sizeof whole);
    }
    for (; j < n; ++j) d[j] = nearest_whole((t[w.row(j)] - t[i]) / period) * period;
    return;
  }
  long long ns[kMaxOfflineWindow];
  const double largest = std::max(std::abs(t[w.begin]), std::abs(t[w.row(n - 1)]));
  const double tolerance = 8 * kDoubleEpsilon * largest * 1e9;  // ns
  bool whole =
      tolerance < 0.25 && n <= kMaxOfflineWindow && (t[w.row(n - 1)] - t[w.begin]) * 1e9 < 0x1p50;
  for (int j = 0; j < n; ++j) {
    d[j] = t[w.row(j)] - t[i];
    if (!whole) continue;
    const double q = d[j] * 1e9, r = nearest_whole(q);
    whole = std::abs(q - r) <= tolerance + 2 * kDoubleEpsilon * std::abs(q);
    ns[j] = static_cast<long long>(r);
  }
  if (whole)
    for (int j = 0; j < n; ++j) d[j] = static_cast<double>(ns[j]) / 1e9;
}

// The weights of offsets d at `order` (n >= 2 rows, order >= 1) into w.value, first, second.
void offset_weights(const double* d, int n, int order, DerivativeWeights& w) {
  const double scale = std::max(-d[0], d[n - 1]);
  double moment[2 * kMaxOrder + 1] = {};  // sum_j s_j^k
  for (int j = 0; j < n; ++j) {
    const double s = d[j] / scale;
    w.first[j] = s;
    double p = 1;
    for (int k = 0; k <= 2 * order; ++k, p *= s) moment[k] += p;
  }
  // N = L L^T.
  double l[kMaxOrder + 1][kMaxOrder + 1];
  for (int a = 0; a <= order; ++a)
    for (int b = 0; b <= a; ++b) {
      double sum = moment[a + b];
      for (int c = 0; c < b; ++c) sum -= l[a][c] * l[b][c];
      l[a][b] = a == b ? std::sqrt(sum) : sum / l[b][b];
    }
  // g[m] = N^-1 e_m, m = 0, 1, 2: forward then back substitution.
  double g[3][kMaxOrder + 1];
  for (int m = 0; m < 3; ++m) {
    for (int a = 0; a <= order; ++a) {
      double sum = a == m ? 1.0 : 0.0;
      for (int c = 0; c < a; ++c) sum -= l[a][c] * g[m][c];
      g[m][a] = sum / l[a][a];
    }
    for (int a = order; a >= 0; --a) {
      double sum = g[m][a];
      for (int c = a + 1; c <= order; ++c) sum -= l[c][a] * g[m][c];
      g[m][a] = sum / l[a][a];
    }
  }
  weight_rows(n, order, scale, g, w);
}

// The weights are a function of the offsets and the order alone: each thread keeps the last ones
// of up to 2 kSets windows (two in each set, the set by a hash of the offsets; a new window
// replaces the one of its set used less recently), found again only by the same order and the
// same offsets to the bit. A regular recording's windows repeat from sample to sample, so the
// weights of each window are computed about once per thread (two ways a set: the few dozen
// windows of a sample seldom evict each other); the results are those of computing them again,
// whatever a thread computed before.
class WeightCache {
 public:
  // The weights of (d, n, order) into w; false when not kept (then `keep` them after computing).
  bool find(const double* d, int n, int order, DerivativeWeights& w) {
    Set& set = set_of(d, n, order);
    for (int way = 0; way < 2; ++way) {
      const Slot& s = set.way[way];
      if (s.order != order || s.n != n || std::memcmp(s.d, d, n * sizeof(double)) != 0) continue;
      std::copy_n(s.value, n, w.value.begin()), std::copy_n(s.first, n, w.first.begin());
      std::copy_n(s.second, n, w.second.begin());
      set.recent = way;
      return true;
    }
    return false;
  }
  void keep(const double* d, int n, int order, const DerivativeWeights& w) {
    Set& set = set_of(d, n, order);
    set.recent = 1 - set.recent;
    Slot& s = set.way[set.recent];
    s.order = order, s.n = n;
    std::copy_n(d, n, s.d);
    std::copy_n(w.value.begin(), n, s.value), std::copy_n(w.first.begin(), n, s.first);
    std::copy_n(w.second.begin(), n, s.second);
  }
  static WeightCache& of_this_thread() {
    thread_local std::unique_ptr<WeightCache> cache(new WeightCache);  // on the heap: 338 kB
    return *cache;
  }

 private:
  static constexpr int kSets = 128;
  struct Slot {
    int order = -1, n = 0;
    double d[kMaxOfflineWindow], value[kMaxOfflineWindow], first[kMaxOfflineWindow],
        second[kMaxOfflineWindow];
  };
  struct Set {
    Slot way[2];
    int recent = 0;  // the way found or kept last
  };
  Set& set_of(const double* d, int n, int order) {
    std::uint64_t a, b, c;
    std::memcpy(&a, &d[0], 8), std::memcpy(&b, &d[1], 8), std::memcpy(&c, &d[n - 1], 8);
    std::uint64_t h = (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^
                      (c * 0x165667B19E3779F9ull) ^ (static_cast<std::uint64_t>(n) << 8 | order);
    h ^= h >> 29;
    return sets_[(h * 0xBF58476D1CE4E5B9ull) >> 57];  // the top 7 bits: kSets
  }
  Set sets_[kSets];
};

}  // namespace

void derivative_weights(const OfflineEstimator& e, const std::vector<double>& t,
                        const Segments& segments, int i, DerivativeWeights& w) {
  const int seg = segments.segment_of[i];
  int begin = 0, end = 0;
  window_range(e, t, segments.begin[seg], segments.end[seg], i, begin, end);
  w.stride = (end - begin + kMaxOfflineWindow - 1) / kMaxOfflineWindow;
  w.begin = i - (i - begin) / w.stride * w.stride;  // every stride-th sample, i among them
  const int n = (end - 1 - w.begin) / w.stride + 1, order = std::min(e.order, n - 1);
  w.count = n;
  w.valid = std::min(order, 2);
  w.value.resize(n);  // every entry written below (no fill first: this runs per sample and window)
  w.first.resize(n);
  w.second.resize(n);
  if (order < 1) {
    std::fill_n(w.value.begin(), n, 0.0), std::fill_n(w.first.begin(), n, 0.0);
    std::fill_n(w.second.begin(), n, 0.0);
    return;
  }
  double d[kMaxOfflineWindow];
  window_offsets(t, i, w, segments.period, d);
  WeightCache& cache = WeightCache::of_this_thread();
  if (cache.find(d, n, order, w)) return;
  offset_weights(d, n, order, w);
  cache.keep(d, n, order, w);
}

namespace {

// apply_weights on series [c0, c0 + kPacks kWidth), their sums in registers over the rows, as
// packs of kWidth doubles that add and multiply lane by lane (GNU vectors: SSE2 registers for
// kWidth 2, AVX2 for 4). The same products and sums in the same order for every width.
template <int kWidth, int kPacks>
__attribute__((always_inline)) inline void apply_block(const DerivativeWeights& w, const double* x,
                                                       int ld, int c0, double* first,
                                                       double* second) {
  typedef double Pack __attribute__((vector_size(kWidth * sizeof(double))));
  Pack f[kPacks] = {}, s[kPacks] = {};
  for (int j = 0; j < w.count; ++j) {
    const double* row = x + static_cast<std::ptrdiff_t>(w.row(j)) * ld + c0;
    for (int p = 0; p < kPacks; ++p) {
      Pack r;
      std::memcpy(&r, row + p * kWidth, sizeof r);
      f[p] += w.first[j] * r;
      if (second) s[p] += w.second[j] * r;
    }
  }
  for (int p = 0; p < kPacks; ++p)
    for (int i = 0; i < kWidth; ++i) {
      first[c0 + p * kWidth + i] = f[p][i];
      if (second) second[c0 + p * kWidth + i] = s[p][i];
    }
}

// Four packs at a time, then one, then one series (a pack of one).
template <int kWidth>
__attribute__((always_inline)) inline void apply_packs(const DerivativeWeights& w, const double* x,
                                                       int ld, int n, double* first,
                                                       double* second) {
  int c0 = 0;
  for (; c0 + 4 * kWidth <= n; c0 += 4 * kWidth)
    apply_block<kWidth, 4>(w, x, ld, c0, first, second);
  for (; c0 + kWidth <= n; c0 += kWidth) apply_block<kWidth, 1>(w, x, ld, c0, first, second);
  for (; c0 < n; ++c0) apply_block<1, 1>(w, x, ld, c0, first, second);
}

#if defined(__x86_64__)
// x86-64 CPUs with AVX2 (without FMA, so bit for bit the SSE2 results) take packs of four.
__attribute__((target("avx2"))) void apply_avx2(const DerivativeWeights& w, const double* x, int ld,
                                                int n, double* first, double* second) {
  apply_packs<4>(w, x, ld, n, first, second);
}
#endif

}  // namespace

void apply_weights(const DerivativeWeights& w, const double* x, int ld, int n, double* first,
                   double* second) {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return apply_avx2(w, x, ld, n, first, second);
#endif
  apply_packs<2>(w, x, ld, n, first, second);
}

void estimate_offline(const OfflineEstimator& e, const std::vector<double>& t,
                      const std::vector<double>& x, double max_gap, std::vector<double>& first,
                      std::vector<double>& second, std::vector<int>& valid) {
  if (e.whole_series()) {
    AutoEstimate a;
    estimate_with_errors(e, t, x.data(), 1, 1, max_gap, a);
    first = a.first, second = a.second, valid = a.valid;
    return;
  }
  const Segments segments = find_segments(t, max_gap);
  const int n = static_cast<int>(t.size());
  first.assign(n, 0.0);
  second.assign(n, 0.0);
  valid.assign(n, 0);
  DerivativeWeights w;
  for (int i = 0; i < n; ++i) {
    derivative_weights(e, t, segments, i, w);
    valid[i] = w.valid;
    for (int j = 0; j < w.count; ++j) {
      first[i] += w.first[j] * x[w.row(j)];
      second[i] += w.second[j] * x[w.row(j)];
    }
  }
}

}  // namespace mbk
