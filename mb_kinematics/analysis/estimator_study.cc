#include "mb_kinematics/analysis/estimator_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "mb_kinematics/core/derivative_estimator.h"

namespace mbk {

double demo_signal(double t, int order) {
  const double a[2] = {0.8, 0.3}, f[2] = {0.7, 2.3}, p[2] = {0.3, 1.1};
  double x = 0;
  for (int i = 0; i < 2; ++i) {
    const double w = 2 * M_PI * f[i], phase = w * t + p[i];
    x += order == 0   ? a[i] * std::sin(phase)
         : order == 1 ? a[i] * w * std::cos(phase)
                      : -a[i] * w * w * std::sin(phase);
  }
  return x;
}

EstimatorResult run_estimator(const std::string& name, double rate, double jitter, double noise,
                              double seconds, int repetitions) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  const int count = static_cast<int>(seconds * rate);
  std::vector<double> t(count), x(count);
  for (int i = 0; i < count; ++i) {
    t[i] = (i + jitter * u(rng)) / rate;
    x[i] = demo_signal(t[i], 0) + noise * n(rng);
  }
  const auto estimator = make_derivative_estimator(name);
  const int latency = estimator->latency();
  double v_err = 0, a_err = 0, v_scale = 0, a_scale = 0;
  volatile double sink = 0;  // keeps the estimates from being optimized away
  std::vector<double> ns;
  for (int r = 0; r < repetitions; ++r) {
    estimator->reset();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < count; ++i) {
      estimator->add(t[i], x[i]);
      double first = 0, second = 0;
      const int valid = estimator->estimate(first, second);
      sink = sink + first + second;
      if (r > 0 || t[i] < 1.0 || valid < 2) continue;  // errors once, after a 1 s warm-up
      const double te = t[i - latency];
      v_err = std::max(v_err, std::abs(first - demo_signal(te, 1)));
      a_err = std::max(a_err, std::abs(second - demo_signal(te, 2)));
      v_scale = std::max(v_scale, std::abs(demo_signal(te, 1)));
      a_scale = std::max(a_scale, std::abs(demo_signal(te, 2)));
    }
    ns.push_back(
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() /
        count);
  }
  std::sort(ns.begin(), ns.end());
  char stream[64], note[96];
  std::snprintf(stream, sizeof stream, "%gHz jitter%g%% noise%g", rate, jitter * 100, noise);
  std::snprintf(note, sizeof note, "velocity error %.2e; latency %d samples", v_err / v_scale,
                latency);
  return {name, stream, ns[ns.size() / 2], ns.front(), ns.back(), a_err / a_scale, note};
}

std::vector<EstimatorResult> estimator_study(bool quick) {
  std::vector<EstimatorResult> out;
  const int repetitions = quick ? 3 : 7;
  for (const std::string& name : derivative_estimator_names())
    for (double rate : {100.0, 1000.0})
      for (double jitter : {0.0, 0.2})
        for (double noise : {0.0, 1e-6, 1e-4})
          out.push_back(run_estimator(name, rate, jitter, noise, quick ? 4.0 : 10.0, repetitions));
  return out;
}

}  // namespace mbk
