#include "bench/dart_peer.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/DegreeOfFreedom.hpp>
#include <dart/dynamics/Joint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/utils/urdf/DartLoader.hpp>
#include <memory>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"

namespace mbk_bench {
namespace {

struct DartRun {
  dart::dynamics::SkeletonPtr skeleton;
  std::vector<dart::dynamics::BodyNode*> nodes;  // those that are our bodies
  std::vector<int> body;                         // our Bk of nodes[i]
  Eigen::VectorXd q, v, a;
  std::vector<Eigen::Matrix3d> rotation;
  std::vector<Eigen::Vector3d> omega, alpha, p, vel, acc;
};

std::unique_ptr<DartRun> make_run(const Scene& scene) {
  auto r = std::make_unique<DartRun>();
  dart::utils::DartLoader loader;
  loader.setOptions(
      dart::utils::DartLoader::Options(nullptr, dart::utils::DartLoader::RootJointType::FIXED));
  r->skeleton = loader.parseSkeletonString(scene.urdf, dart::common::Uri("file:///"));
  if (!r->skeleton) {
    std::fprintf(stderr, "%s: DART cannot read the URDF\n", scene.name.c_str());
    std::exit(1);
  }
  const mbk::Model& model = scene.model;
  const mbk::JointState<double> state = random_state(model, 1);
  const size_t n = r->skeleton->getNumDofs();
  r->q.setZero(n);
  r->v.setZero(n);
  r->a.setZero(n);
  for (size_t d = 0; d < n; ++d) {
    const int c = model.coordinate_index(r->skeleton->getDof(d)->getJoint()->getName());
    if (c < 0) {
      std::fprintf(stderr, "%s: DART's dof %zu is not one of ours\n", scene.name.c_str(), d);
      std::exit(1);
    }
    r->q[d] = state.position[c];
    r->v[d] = state.velocity[c];
    r->a[d] = state.acceleration[c];
  }
  for (size_t b = 0; b < r->skeleton->getNumBodyNodes(); ++b) {
    dart::dynamics::BodyNode* node = r->skeleton->getBodyNode(b);
    const int k = model.body_index(node->getName());
    if (k < 1) continue;
    r->nodes.push_back(node);
    r->body.push_back(k);
  }
  r->rotation.assign(r->nodes.size(), Eigen::Matrix3d::Zero());
  for (auto* out : {&r->omega, &r->alpha, &r->p, &r->vel, &r->acc})
    out->assign(r->nodes.size(), Eigen::Vector3d::Zero());
  return r;
}

void full_state(DartRun& r) {
  r.skeleton->setPositions(r.q);
  r.skeleton->setVelocities(r.v);
  r.skeleton->setAccelerations(r.a);
  for (size_t i = 0; i < r.nodes.size(); ++i) {
    const dart::dynamics::BodyNode* node = r.nodes[i];
    r.rotation[i] = node->getWorldTransform().linear();
    r.omega[i] = node->getAngularVelocity();
    r.alpha[i] = node->getAngularAcceleration();
    r.p[i] = node->getCOM();
    r.vel[i] = node->getCOMLinearVelocity();
    r.acc[i] = node->getCOMLinearAcceleration();
  }
}

// DART's bodies at the run's state (check_agreement).
std::vector<PeerBody> bodies_of(DartRun& r) {
  full_state(r);
  std::vector<PeerBody> bodies;
  for (size_t i = 0; i < r.nodes.size(); ++i)
    bodies.push_back(
        {r.body[i], r.rotation[i], r.p[i], r.omega[i], r.alpha[i], r.vel[i], r.acc[i]});
  return bodies;
}

}  // namespace

void register_dart(const Scene& scene) {
  std::shared_ptr<DartRun> r = make_run(scene);
  check_agreement(scene, "DART", bodies_of(*r), scene.model.body_count());
  const double bodies = static_cast<double>(r->nodes.size());
  benchmark::RegisterBenchmark(("dart/" + scene.name + "/full").c_str(),
                               [r, bodies](benchmark::State& st) {
                                 const int n = static_cast<int>(r->q.size());
                                 int64_t i = 0;
                                 for (auto _ : st) {
                                   nudge(r->q.data(), r->v.data(), n, i++);
                                   full_state(*r);
                                   benchmark::DoNotOptimize(r->acc.back().data());
                                   benchmark::ClobberMemory();
                                 }
                                 st.counters["bodies"] = bodies;
                               });
}

}  // namespace mbk_bench
