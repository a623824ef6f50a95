#include "mb_kinematics/analysis/estimator_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "mb_kinematics/core/derivative_estimator.h"

namespace mbk {

EstimatorResult run_estimator(const std::string& name, const std::vector<Wave>& waves, double rate,
                              double jitter, double noise, double seconds, int repetitions) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  const int count = static_cast<int>(seconds * rate), m = static_cast<int>(waves.size());
  std::vector<double> t(count), x(static_cast<size_t>(count) * m);  // x[i * m + c]
  for (int i = 0; i < count; ++i) {
    t[i] = (i + jitter * u(rng)) / rate;
    for (int c = 0; c < m; ++c) x[i * m + c] = waves[c].at(t[i], 0) + noise * n(rng);
  }
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
  char stream[64], note[96];
  std::snprintf(stream, sizeof stream, "%gHz jitter%g%% noise%g", rate, jitter * 100, noise);
  std::snprintf(note, sizeof note, "velocity error %.2e; latency %d samples", v_err / v_scale,
                latency);
  return {name, stream, ns[ns.size() / 2], ns.front(), ns.back(), a_err / a_scale, note};
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
  return out;
}

}  // namespace mbk
