#include "bench/pinocchio_peer.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/multibody/data.hpp>
#include <pinocchio/multibody/model.hpp>
#include <pinocchio/parsers/urdf.hpp>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics.h"

namespace mbk_bench {
namespace {

// One Pinocchio joint and what it stands for in our model.
struct PinJoint {
  int idx_q = 0;
  int idx_v = 0;
  bool cos_sin = false;  // continuous joint: q = (cos x, sin x)
  int body = 0;          // our Bk
  Eigen::Vector3d lever = Eigen::Vector3d::Zero();
};

struct PinRun {
  pinocchio::Model model;
  std::unique_ptr<pinocchio::Data> data;
  std::vector<PinJoint> joints;  // joints[i - 1] is Pinocchio's joint i
  Eigen::VectorXd x, q, v, a;    // x: one value per joint (angle or translation)
  std::vector<Eigen::Vector3d> omega, alpha, p, vel, acc;  // per joint, world components
};

// Joint by joint from our model (revolute joints only): Pinocchio's URDF parser does not cope
// with long chains (README "Speed").
pinocchio::Model build_from(const mbk::Model& model) {
  pinocchio::Model pin;
  std::vector<pinocchio::JointIndex> id(model.bodies.size(), 0);
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& body = model.bodies[k];
    if (body.joint.type != mbk::JointType::kRevolute) {
      std::fprintf(stderr, "pinocchio: only revolute joints are built directly\n");
      std::exit(1);
    }
    const pinocchio::SE3 placement(body.joint.rotation, body.joint.offset);
    const Eigen::Vector3d& a = body.joint.axis;
    const pinocchio::JointIndex parent = id[body.lower];
    const std::string& name = body.joint.name;
    if (a == Eigen::Vector3d::UnitX())
      id[k] = pin.addJoint(parent, pinocchio::JointModelRX(), placement, name);
    else if (a == Eigen::Vector3d::UnitY())
      id[k] = pin.addJoint(parent, pinocchio::JointModelRY(), placement, name);
    else if (a == Eigen::Vector3d::UnitZ())
      id[k] = pin.addJoint(parent, pinocchio::JointModelRZ(), placement, name);
    else
      id[k] = pin.addJoint(parent, pinocchio::JointModelRevoluteUnaligned(a), placement, name);
    pin.appendBodyToJoint(
        id[k], pinocchio::Inertia(body.mass, body.mass_center, Eigen::Matrix3d::Identity() * 1e-3));
  }
  return pin;
}

std::unique_ptr<PinRun> make_run(const Scene& scene) {
  auto r = std::make_unique<PinRun>();
  if (scene.parse_urdf)
    pinocchio::urdf::buildModelFromXML(scene.urdf, r->model);
  else
    r->model = build_from(scene.model);
  r->data = std::make_unique<pinocchio::Data>(r->model);
  const mbk::Model& model = scene.model;
  const mbk::JointState<double> state = random_state(model, 1);
  r->q = pinocchio::neutral(r->model);
  r->x.setZero(r->model.nv);
  r->v.setZero(r->model.nv);
  r->a.setZero(r->model.nv);
  for (pinocchio::JointIndex i = 1; i < r->model.joints.size(); ++i) {
    const auto& joint = r->model.joints[i];
    PinJoint j;
    j.idx_q = joint.idx_q();
    j.idx_v = joint.idx_v();
    j.cos_sin = joint.nq() == 2 && joint.nv() == 1;
    for (int k = 1; k <= model.body_count() && j.body == 0; ++k)
      if (model.bodies[k].joint.name == r->model.names[i]) j.body = k;
    const int c = model.coordinate_index(r->model.names[i]);
    if (j.body == 0 || c < 0 || joint.nv() != 1) {
      std::fprintf(stderr, "pinocchio: joint %s is not one of ours\n", r->model.names[i].c_str());
      std::exit(1);
    }
    j.lever = r->model.inertias[i].lever();
    r->x[j.idx_v] = state.position[c];
    r->v[j.idx_v] = state.velocity[c];
    r->a[j.idx_v] = state.acceleration[c];
    r->joints.push_back(j);
  }
  for (auto* out : {&r->omega, &r->alpha, &r->p, &r->vel, &r->acc})
    out->assign(r->model.joints.size(), Eigen::Vector3d::Zero());
  return r;
}

// Angles to Pinocchio's configuration: (cos, sin) for continuous joints.
void to_configuration(PinRun& r) {
  for (const PinJoint& j : r.joints) {
    const double x = r.x[j.idx_v];
    if (j.cos_sin) {
      r.q[j.idx_q] = std::cos(x);
      r.q[j.idx_q + 1] = std::sin(x);
    } else {
      r.q[j.idx_q] = x;
    }
  }
}

// Our full state from Pinocchio's oMi and local spatial velocity and acceleration: omega,
// alpha, and the position, velocity and (classical) acceleration of each mass center.
void mass_center_kinematics(PinRun& r) {
  for (size_t n = 0; n < r.joints.size(); ++n) {
    const size_t i = n + 1;
    const Eigen::Vector3d& c = r.joints[n].lever;
    const pinocchio::SE3& m = r.data->oMi[i];
    const pinocchio::Motion& v = r.data->v[i];
    const pinocchio::Motion& a = r.data->a[i];
    const Eigen::Vector3d w = v.angular();
    const Eigen::Vector3d vc = v.linear() + w.cross(c);
    r.p[i] = m.act(c);
    r.omega[i] = m.rotation() * w;
    r.vel[i] = m.rotation() * vc;
    r.alpha[i] = m.rotation() * a.angular();
    r.acc[i] = m.rotation() * (a.linear() + a.angular().cross(c) + w.cross(vc));
  }
}

void check_agreement(const Scene& scene, PinRun& r) {
  const mbk::JointState<double> state = random_state(scene.model, 1);
  mbk::Data<double> data(scene.model);
  mbk::forward_kinematics(scene.model, state, data);
  to_configuration(r);
  pinocchio::forwardKinematics(r.model, *r.data, r.q, r.v, r.a);
  mass_center_kinematics(r);
  double e = 0;
  for (size_t n = 0; n < r.joints.size(); ++n) {
    const int k = r.joints[n].body, i = static_cast<int>(n) + 1;
    e = std::max(e, disagreement(r.data->oMi[i].rotation(), data.rotation[k]));
    e = std::max(e, disagreement(r.p[i], data.mass_center[k]));
    e = std::max(e, disagreement(r.omega[i], data.omega[k]));
    e = std::max(e, disagreement(r.alpha[i], data.alpha[k]));
    e = std::max(e, disagreement(r.vel[i], data.mass_center_velocity[k]));
    e = std::max(e, disagreement(r.acc[i], data.mass_center_acceleration[k]));
  }
  if (!(e < 1e-9)) {
    std::fprintf(stderr, "%s: Pinocchio and ours disagree (%g)\n", scene.name.c_str(), e);
    std::exit(1);
  }
}

}  // namespace

void register_pinocchio(const Scene& scene) {
  std::shared_ptr<PinRun> r = make_run(scene);
  check_agreement(scene, *r);
  const double bodies = static_cast<double>(r->joints.size());
  benchmark::RegisterBenchmark(("pinocchio/" + scene.name + "/pose").c_str(),
                               [r, bodies](benchmark::State& st) {
                                 int64_t i = 0;
                                 for (auto _ : st) {
                                   nudge(r->x.data(), nullptr, r->model.nv, i++);
                                   to_configuration(*r);
                                   pinocchio::forwardKinematics(r->model, *r->data, r->q);
                                   benchmark::DoNotOptimize(r->data->oMi.back());
                                   benchmark::ClobberMemory();
                                 }
                                 st.counters["bodies"] = bodies;
                               });
  benchmark::RegisterBenchmark(
      ("pinocchio/" + scene.name + "/full").c_str(), [r, bodies](benchmark::State& st) {
        int64_t i = 0;
        for (auto _ : st) {
          nudge(r->x.data(), r->v.data(), r->model.nv, i++);
          to_configuration(*r);
          pinocchio::forwardKinematics(r->model, *r->data, r->q, r->v, r->a);
          mass_center_kinematics(*r);
          benchmark::DoNotOptimize(r->acc.back().data());
          benchmark::ClobberMemory();
        }
        st.counters["bodies"] = bodies;
      });
}

}  // namespace mbk_bench
