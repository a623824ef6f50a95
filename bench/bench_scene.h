// What every benchmark of kinematics_benchmark shares: the scenes (a model, its URDF when peers
// can read it) and one way to vary the state between iterations.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
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

// 29 revolute joints in the shape of Pinocchio's simple_humanoid: from the waist, two legs of 6
// (hip roll, pitch, yaw, knee, ankle pitch, roll), a waist of 3 and two arms of 7.
inline mbk::Model humanoid29() {
  struct J {
    std::string name, parent;  // parent "": the waist (the frame R)
    double y, z;               // q_k = (0, y, z)
    int axis;                  // 0, 1, 2: x, y, z
  };
  std::vector<J> joints = {
      {"WAIST_P", "", 0, 0, 1}, {"WAIST_R", "WAIST_P", 0, 0, 0}, {"CHEST", "WAIST_R", 0, 0.35, 2}};
  for (const std::string side : {"R", "L"}) {
    const double sign = side == "R" ? -1 : 1;
    const std::string leg = side + "LEG_", arm = side + "ARM_";
    const std::vector<J> limbs = {{leg + "HIP_R", "", sign * 0.09, 0, 0},
                                  {leg + "HIP_P", leg + "HIP_R", 0, 0, 1},
                                  {leg + "HIP_Y", leg + "HIP_P", 0, -0.3535, 2},
                                  {leg + "KNEE", leg + "HIP_Y", 0, 0, 1},
                                  {leg + "ANKLE_P", leg + "KNEE", 0, -0.3, 1},
                                  {leg + "ANKLE_R", leg + "ANKLE_P", 0, 0, 0},
                                  {arm + "SHOULDER_P", "CHEST", sign * 0.21, 0, 1},
                                  {arm + "SHOULDER_R", arm + "SHOULDER_P", 0, 0, 0},
                                  {arm + "SHOULDER_Y", arm + "SHOULDER_R", 0, -0.263, 2},
                                  {arm + "ELBOW", arm + "SHOULDER_Y", 0, 0, 1},
                                  {arm + "WRIST_Y", arm + "ELBOW", 0, -0.247, 2},
                                  {arm + "WRIST_P", arm + "WRIST_Y", 0, 0, 1},
                                  {arm + "WRIST_R", arm + "WRIST_P", 0, 0, 0}};
    joints.insert(joints.end(), limbs.begin(), limbs.end());
  }
  mbk::Model model;
  model.frame = "WAIST_LINK0";
  model.bodies.resize(joints.size() + 1);
  for (size_t i = 0; i < joints.size(); ++i) {
    const J& j = joints[i];
    mbk::Body& body = model.bodies[i + 1];
    body.name = j.name + "_LINK";
    body.joint.name = j.name;
    body.joint.type = mbk::JointType::kRevolute;
    body.joint.offset = mbk::Vec3<double>(0.0, j.y, j.z);
    body.joint.axis = mbk::Vec3<double>::Unit(j.axis);
    body.lower = j.parent.empty() ? 0 : model.body_index(j.parent + "_LINK");
    body.mass_center = mbk::Vec3<double>(0.01, 0.0, j.z < 0 ? -0.1 : 0.05);
    body.mass = 2.0;
  }
  mbk::finalize_model(model);
  return model;
}

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

// One body as a peer computes it, in world components: our body number k, its orientation, and
// its mass center's position, velocity and acceleration with the body's omega and alpha.
struct PeerBody {
  int k;
  Eigen::Matrix3d rotation;
  Eigen::Vector3d p, omega, alpha, velocity, acceleration;
};

// Before a peer is timed: its bodies at random_state(model, 1) against forward_kinematics', all
// of them (and, with `bodies` >= 0, that many) agreeing to 1e-9 (disagreement); else the run
// stops (exit 1) naming the scene and the peer.
inline void check_agreement(const Scene& scene, const char* peer, const std::vector<PeerBody>& got,
                            int bodies = -1) {
  mbk::Data<double> data(scene.model);
  mbk::forward_kinematics(scene.model, random_state(scene.model, 1), data);
  double e = bodies < 0 || static_cast<int>(got.size()) == bodies ? 0.0 : 1.0;
  for (const PeerBody& b : got) {
    e = std::max(e, disagreement(b.rotation, data.rotation[b.k]));
    e = std::max(e, disagreement(b.p, data.mass_center[b.k]));
    e = std::max(e, disagreement(b.omega, data.omega[b.k]));
    e = std::max(e, disagreement(b.alpha, data.alpha[b.k]));
    e = std::max(e, disagreement(b.velocity, data.mass_center_velocity[b.k]));
    e = std::max(e, disagreement(b.acceleration, data.mass_center_acceleration[b.k]));
  }
  if (!(e < 1e-9)) {
    std::fprintf(stderr, "%s: %s and ours disagree (%g)\n", scene.name.c_str(), peer, e);
    std::exit(1);
  }
}

}  // namespace mbk_bench
