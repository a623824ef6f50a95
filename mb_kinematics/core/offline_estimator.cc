#include "mb_kinematics/core/offline_estimator.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mbk {
namespace {

constexpr int kMaxOrder = 5;

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
  begin = static_cast<int>(std::lower_bound(t.begin() + sb, t.begin() + i, lo) - t.begin());
  end = static_cast<int>(std::upper_bound(t.begin() + i, t.begin() + se, hi) - t.begin());
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
  static const std::vector<std::string> names = {
      "centered_0.4s_4", "centered_0.1s_4", "centered_0.2s_4", "centered_0.3s_4",
      "centered_0.4s_5", "centered_9_4",    "centered_15_3"};
  return names;
}

const char* default_offline_estimator() { return offline_estimator_names().front().c_str(); }

OfflineEstimator make_offline_estimator(const std::string& name) {
  OfflineEstimator e;
  e.name = name;
  int used = 0, samples = 0, order = 0;
  double seconds = 0;
  if (std::sscanf(name.c_str(), "centered_%lfs_%d%n", &seconds, &order, &used) == 2 &&
      used == static_cast<int>(name.size())) {
    e.window_seconds = seconds;
  } else if (std::sscanf(name.c_str(), "centered_%d_%d%n", &samples, &order, &used) == 2 &&
             used == static_cast<int>(name.size())) {
    e.window_samples = samples;
  } else {
    throw std::invalid_argument("unknown offline estimator '" + name +
                                "' (known: centered_<samples>_<order>, e.g. centered_9_4, or "
                                "centered_<seconds>s_<order>, e.g. centered_0.1s_3)");
  }
  e.order = order;
  const bool window_ok = e.window_seconds != 0
                             ? std::isfinite(seconds) && seconds > 0
                             : samples % 2 == 1 && samples > order && samples <= kMaxOfflineWindow;
  if (order < 2 || order > kMaxOrder || !window_ok)
    throw std::invalid_argument("offline estimator '" + name +
                                "': need 2 <= order <= 5 and an odd sample window above the "
                                "order (at most 41) or a positive time window");
  return e;
}

Segments find_segments(const std::vector<double>& t, double max_gap) {
  Segments s;
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

// Least squares in s = (t_j - t_i) / scale: c = (A^T A)^-1 A^T x, x'(t_i) = c1 / scale,
// x''(t_i) = 2 c2 / scale^2; the weights are the rows of (A^T A)^-1 A^T for c1 and c2.
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
  w.first.assign(n, 0.0);
  w.second.assign(n, 0.0);
  if (order < 1) return;
  const double scale = std::max(t[i] - t[w.begin], t[w.row(n - 1)] - t[i]);
  using Mat =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxOrder + 1, kMaxOrder + 1>;
  using Row = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kMaxOrder + 1>;
  Mat normal = Mat::Zero(order + 1, order + 1);
  Row a(order + 1);
  for (int j = 0; j < n; ++j) {
    const double s = (t[w.row(j)] - t[i]) / scale;
    double p = 1;
    for (int c = 0; c <= order; ++c, p *= s) a[c] = p;
    normal.noalias() += a.transpose() * a;
  }
  const Mat inverse = normal.ldlt().solve(Mat::Identity(order + 1, order + 1));
  for (int j = 0; j < n; ++j) {
    const double s = (t[w.row(j)] - t[i]) / scale;
    double p = 1;
    for (int c = 0; c <= order; ++c, p *= s) a[c] = p;
    w.first[j] = a.dot(inverse.col(1)) / scale;
    if (order >= 2) w.second[j] = 2 * a.dot(inverse.col(2)) / (scale * scale);
  }
}

void estimate_offline(const OfflineEstimator& e, const std::vector<double>& t,
                      const std::vector<double>& x, double max_gap, std::vector<double>& first,
                      std::vector<double>& second, std::vector<int>& valid) {
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
