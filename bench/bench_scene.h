// What every benchmark of kinematics_benchmark shares: the scenes (a model, its URDF when peers
// can read it) and one way to vary the state between iterations.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk_bench {

struct Scene {
  std::string name;
  mbk::Model model;
  std::string urdf;  // the same model as URDF; empty: no KDL and DART (they read URDF only)
  bool parse_urdf;   // peers load `urdf` with their parsers (else a peer builds `model`)
  bool peers;        // run the peers (their memory or time grows faster than N: at most
                     // 1000 bodies; Pinocchio's Data alone holds N x N matrices)
  std::string mjcf = "";  // an MJCF file of the model: MuJoCo alone reads it (not the others)
};

inline mbk::JointState<double> random_state(const mbk::Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  return mbk::random_state(model, rng);
}

// Nudges coordinate i % n by a tiny amount: the state differs every iteration at no real cost.
inline void nudge(double* q, double* v, int n, int64_t i) {
  const int c = static_cast<int>(i % n);
  q[c] += 1e-9;
  if (v) v[c] -= 1e-9;
}

// Largest |a - b| over coefficients, relative to 1 + |b|: how two peers agree before timing.
template <typename A, typename B>
double disagreement(const A& a, const B& b) {
  return ((a - b).array().abs() / (1.0 + b.array().abs())).maxCoeff();
}

}  // namespace mbk_bench
