#include "mb_kinematics/analysis/estimator_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/butterworth_estimator.h"
#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/estimation/offline_estimator.h"

namespace mbk {

namespace {

std::string stream_name(double rate, double jitter, double noise) {
  char stream[64];
  std::snprintf(stream, sizeof stream, "%gHz jitter%g%% noise%g", rate, jitter * 100, noise);
  return stream;
}

}  // namespace

void study_stream(const std::vector<Wave>& waves, double rate, double jitter, double noise,
                 double seconds, std::vector<double>& t, std::vector<double>& x) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  const int count = static_cast<int>(seconds * rate), m = static_cast<int>(waves.size());
  t.resize(count);
  x.resize(static_cast<size_t>(count) * m);
  for (int i = 0; i < count; ++i) {
    t[i] = (i + jitter * u(rng)) / rate;
    for (int c = 0; c < m; ++c) x[i * m + c] = waves[c].at(t[i], 0) + noise * n(rng);
  }
}

EstimatorResult run_estimator(const std::string& name, const std::vector<Wave>& waves, double rate,
                              double jitter, double noise, double seconds, int repetitions) {
  std::vector<double> t, x;
  study_stream(waves, rate, jitter, noise, seconds, t, x);
  const int count = static_cast<int>(t.size()), m = static_cast<int>(waves.size());
  std::vector<std::unique_ptr<DerivativeEstimator>> estimators;
  for (int c = 0; c < m; ++c) estimators.push_back(make_derivative_estimator(name));
  const int latency = estimators.front()->latency();
  double v_err = 0, a_err = 0, v_scale = 0, a_scale = 0;
  volatile double sink = 0;  // keeps the estimates from being optimized away
  std::vector<double> ns;
  for (int r = 0; r < repetitions; ++r) {
    for (auto& e : estimators) e->reset();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < count; ++i) {
      for (int c = 0; c < m; ++c) {
        estimators[c]->add(t[i], x[i * m + c]);
        double first = 0, second = 0;
        const int valid = estimators[c]->estimate(first, second);
        sink = sink + first + second;
        if (r > 0 || t[i] < 1.0 || valid < 2) continue;  // errors once, after a 1 s warm-up
        const double te = t[i - latency];
        v_err = std::max(v_err, std::abs(first - waves[c].at(te, 1)));
        a_err = std::max(a_err, std::abs(second - waves[c].at(te, 2)));
        v_scale = std::max(v_scale, std::abs(waves[c].at(te, 1)));
        a_scale = std::max(a_scale, std::abs(waves[c].at(te, 2)));
      }
    }
    const double elapsed =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    ns.push_back(elapsed / (static_cast<double>(count) * m));
  }
  std::sort(ns.begin(), ns.end());
  char note[96];
  std::snprintf(note, sizeof note, "velocity error %.2e; latency %d samples", v_err / v_scale,
                latency);
  return {name,
          stream_name(rate, jitter, noise),
          ns[ns.size() / 2],
          ns.front(),
          ns.back(),
          a_err / a_scale,
          note};
}

namespace {

// Both derivatives of the m coordinates sampled at t (x[i * m + c]) as mbk bag computes them:
// the fixed estimators' weights once per sample for all coordinates; "auto" per coordinate.
void offline_derivatives(const OfflineEstimator& e, const std::vector<double>& t,
                         const std::vector<double>& x, int m, AutoEstimate& a) {
  if (e.whole_series()) return estimate_with_errors(e, t, x.data(), m, m, default_max_gap(t), a);
  const int count = static_cast<int>(t.size());
  const Segments segments = find_segments(t, default_max_gap(t));
  DerivativeWeights w;
  a.first.assign(x.size(), 0.0);
  a.second.assign(x.size(), 0.0);
  for (int i = 0; i < count; ++i) {
    derivative_weights(e, t, segments, i, w);
    for (int j = 0; j < w.count; ++j)
      for (int c = 0; c < m; ++c) {
        a.first[i * m + c] += w.first[j] * x[w.row(j) * m + c];
        a.second[i * m + c] += w.second[j] * x[w.row(j) * m + c];
      }
  }
}

}  // namespace

OfflineAccuracy offline_accuracy(const std::vector<Wave>& waves, const std::vector<double>& t,
                                 const AutoEstimate& a) {
  const int m = static_cast<int>(waves.size());
  const double margin = 0.5;  // s: "away from the ends"
  double scale[2] = {0, 0};
  OfflineAccuracy out;
  for (size_t i = 0; i < t.size(); ++i)
    for (int c = 0; c < m; ++c)
      for (int d = 1; d <= 2; ++d) {
        const double exact = waves[c].at(t[i], d);
        const double error = std::abs((d == 1 ? a.first : a.second)[i * m + c] - exact);
        const bool inside = t[i] >= t.front() + margin && t[i] <= t.back() - margin;
        scale[d - 1] = std::max(scale[d - 1], std::abs(exact));
        double& all = d == 1 ? out.velocity : out.acceleration;
        double& away = d == 1 ? out.velocity_inside : out.acceleration_inside;
        all = std::max(all, error);
        if (inside) away = std::max(away, error);
      }
  out.velocity /= scale[0], out.velocity_inside /= scale[0];
  out.acceleration /= scale[1], out.acceleration_inside /= scale[1];
  return out;
}

OfflineAccuracy offline_accuracy(const std::string& name, const std::vector<Wave>& waves,
                                 double rate, double jitter, double noise, double seconds) {
  std::vector<double> t, x;
  study_stream(waves, rate, jitter, noise, seconds, t, x);
  AutoEstimate a;
  offline_derivatives(make_offline_estimator(name), t, x, static_cast<int>(waves.size()), a);
  return offline_accuracy(waves, t, a);
}

EstimatorResult run_offline_estimator(const std::string& name, const std::vector<Wave>& waves,
                                      double rate, double jitter, double noise, double seconds,
                                      int repetitions) {
  std::vector<double> t, x;
  study_stream(waves, rate, jitter, noise, seconds, t, x);
  const int count = static_cast<int>(t.size()), m = static_cast<int>(waves.size());
  const OfflineEstimator e = make_offline_estimator(name);
  AutoEstimate a;  // the estimates of every sample and coordinate (a.first, a.second)
  std::vector<double> ns;
  for (int r = 0; r < repetitions; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    offline_derivatives(e, t, x, m, a);
    const double elapsed =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    ns.push_back(elapsed / (static_cast<double>(count) * m));
  }
  const OfflineAccuracy accuracy = offline_accuracy(waves, t, a);
  std::sort(ns.begin(), ns.end());
  char note[96];
  std::snprintf(note, sizeof note, "velocity error %.2e; latency 0 samples; offline",
                accuracy.velocity);
  return {name,
          stream_name(rate, jitter, noise),
          ns[ns.size() / 2],
          ns.front(),
          ns.back(),
          accuracy.acceleration,
          note};
}

std::vector<Wave> human_like_waves(const Model& model) {
  std::vector<Wave> waves = demo_waves(model);
  for (size_t i = 0; i < waves.size(); ++i) {
    const double f = 0.2 * std::pow(25.0, std::fmod(0.618034 * (i + 1), 1.0));  // 0.2 to 5 Hz
    waves[i].w = 2 * M_PI * f;
    waves[i].a /= std::max(1.0, f);
  }
  return waves;
}

std::vector<EstimatorResult> estimator_study(const std::vector<Wave>& waves, bool quick) {
  std::vector<EstimatorResult> out;
  const int repetitions = quick ? 1 : 3;
  for (const std::string& name : derivative_estimator_names())
    for (double rate : {100.0, 1000.0})
      for (double jitter : {0.0, 0.2})
        for (double noise : {0.0, 1e-6, 1e-4})
          out.push_back(
              run_estimator(name, waves, rate, jitter, noise, quick ? 4.0 : 10.0, repetitions));
  for (const std::string& name : offline_estimator_names())
    for (double rate : {100.0, 1000.0})
      for (double jitter : {0.0, 0.2})
        for (double noise : {0.0, 1e-6, 1e-4, 1e-3, 1e-2})
          out.push_back(run_offline_estimator(name, waves, rate, jitter, noise, quick ? 4.0 : 10.0,
                                              repetitions));
  return out;
}

}  // namespace mbk
