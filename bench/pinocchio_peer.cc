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
#include "mb_kinematics/core/kinematics_double.h"

namespace mbk_bench {
namespace {

// One Pinocchio joint and what it stands for in our model.
struct PinJoint {
  mbk::JointType type = mbk::JointType::kRevolute;  // ours: revolute, ball or free 1-2-3
  int idx_q = 0;
  int idx_v = 0;         // also where its coordinates are in x, xd, xdd (nv = our nq)
  bool cos_sin = false;  // continuous joint: q = (cos x, sin x)
  int body = 0;          // our Bk
  Eigen::Vector3d lever = Eigen::Vector3d::Zero();
};

struct PinRun {
  pinocchio::Model model;
  std::unique_ptr<pinocchio::Data> data;
  std::vector<PinJoint> joints;  // joints[i - 1] is Pinocchio's joint i
  // Our coordinates, their first and second derivatives (angles, 1-2-3 angles, translations),
  // in Pinocchio's velocity layout; q, v, a: Pinocchio's.
  Eigen::VectorXd x, xd, xdd, q, v, a;
  std::vector<Eigen::Vector3d> omega, alpha, p, vel, acc;  // per joint, world components
};

// Joint by joint from our model (revolute, ball and free 1-2-3 joints): Pinocchio's URDF parser
// does not cope with long chains, and URDF has no ball joint (doc/speed.md). A ball joint is
// Pinocchio's spherical joint, a free joint its free flyer.
pinocchio::Model build_from(const mbk::Model& model) {
  pinocchio::Model pin;
  std::vector<pinocchio::JointIndex> id(model.bodies.size(), 0);
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& body = model.bodies[k];
    const pinocchio::SE3 placement(body.joint.rotation, body.joint.offset);
    const Eigen::Vector3d& a = body.joint.axis;
    const pinocchio::JointIndex parent = id[body.lower];
    const std::string& name = body.joint.name;
    if (body.joint.type == mbk::JointType::kBall123)
      id[k] = pin.addJoint(parent, pinocchio::JointModelSpherical(), placement, name);
    else if (body.joint.type == mbk::JointType::kFree123)
      id[k] = pin.addJoint(parent, pinocchio::JointModelFreeFlyer(), placement, name);
    else if (body.joint.type != mbk::JointType::kRevolute) {
      std::fprintf(stderr, "pinocchio: only revolute, ball and free 1-2-3 joints are built\n");
      std::exit(1);
    } else if (a == Eigen::Vector3d::UnitX())
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

// Our joint of Pinocchio's joint i (by name): its body, type and first coordinate, or exits.
PinJoint our_joint(const mbk::Model& model, const pinocchio::Model& pin, pinocchio::JointIndex i,
                   int& coordinate) {
  const auto& joint = pin.joints[i];
  PinJoint j;
  j.idx_q = joint.idx_q();
  j.idx_v = joint.idx_v();
  j.cos_sin = joint.nq() == 2 && joint.nv() == 1;
  for (int k = 1; k <= model.body_count() && j.body == 0; ++k)
    if (model.bodies[k].joint.name == pin.names[i]) j.body = k;
  coordinate = -1;
  if (j.body > 0) {
    j.type = model.bodies[j.body].joint.type;
    coordinate =
        joint.nv() == 1 ? model.coordinate_index(pin.names[i]) : model.bodies[j.body].q_index;
  }
  const int nq = j.body > 0 ? mbk::coordinate_count(j.type) : 0;
  if (coordinate < 0 || nq != joint.nv()) {
    std::fprintf(stderr, "pinocchio: joint %s is not one of ours\n", pin.names[i].c_str());
    std::exit(1);
  }
  j.lever = pin.inertias[i].lever();
  return j;
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
  for (auto* out : {&r->x, &r->xd, &r->xdd, &r->v, &r->a}) out->setZero(r->model.nv);
  for (pinocchio::JointIndex i = 1; i < r->model.joints.size(); ++i) {
    int c = 0;
    const PinJoint j = our_joint(model, r->model, i, c);
    const int n = r->model.joints[i].nv();
    r->x.segment(j.idx_v, n) = state.position.segment(c, n);
    r->xd.segment(j.idx_v, n) = state.velocity.segment(c, n);
    r->xdd.segment(j.idx_v, n) = state.acceleration.segment(c, n);
    r->joints.push_back(j);
  }
  for (auto* out : {&r->omega, &r->alpha, &r->p, &r->vel, &r->acc})
    out->assign(r->model.joints.size(), Eigen::Vector3d::Zero());
  return r;
}

// 1-2-3 angles (alpha, beta, gamma; S = A(alpha) B(beta) C(gamma)) and their derivatives to
// Pinocchio's spherical joint: the unit quaternion (x, y, z, w) at q, and, with the rates
// (`rates` non-null), the angular velocity in the child's frame at v and its time derivative
// at a (Pinocchio's joint acceleration, the derivative of v's components).
void angles_123_to_spherical(const double* x, const double* xd, const double* xdd, double* q,
                             double* v, double* a) {
  using Eigen::Vector3d;
  const Eigen::Quaterniond e = Eigen::AngleAxisd(x[0], Vector3d::UnitX()) *
                               Eigen::AngleAxisd(x[1], Vector3d::UnitY()) *
                               Eigen::AngleAxisd(x[2], Vector3d::UnitZ());
  Eigen::Map<Eigen::Vector4d> quaternion(q);
  quaternion = e.coeffs();
  if (!xd) return;
  const double sb = std::sin(x[1]), cb = std::cos(x[1]), sg = std::sin(x[2]), cg = std::cos(x[2]);
  // w = alpha' u + beta' w2 + gamma' e3 in the child's frame, u = (cb cg, -cb sg, sb),
  // w2 = (sg, cg, 0); its derivative adds alpha' u' + beta' w2'.
  const Vector3d u(cb * cg, -cb * sg, sb), w2(sg, cg, 0);
  const Vector3d u_dot(-sb * cg * xd[1] - cb * sg * xd[2], sb * sg * xd[1] - cb * cg * xd[2],
                       cb * xd[1]);
  const Vector3d w2_dot(cg * xd[2], -sg * xd[2], 0);
  Eigen::Map<Vector3d> omega(v), omega_dot(a);
  omega = xd[0] * u + xd[1] * w2 + Vector3d(0, 0, xd[2]);
  omega_dot = xdd[0] * u + xd[0] * u_dot + xdd[1] * w2 + xd[1] * w2_dot + Vector3d(0, 0, xdd[2]);
}

// Our coordinates to Pinocchio's configuration (and, `full`, velocity and acceleration):
// (cos, sin) for continuous joints; quaternions and angular velocities in the child's frame for
// ball joints; for free joints also the translation in the parent's frame, its velocity in the
// child's frame and that velocity's time derivative (R^T s'' - w x R^T s').
void to_configuration(PinRun& r, bool full) {
  for (const PinJoint& j : r.joints) {
    const double* x = r.x.data() + j.idx_v;
    double* q = r.q.data() + j.idx_q;
    double* v = r.v.data() + j.idx_v;
    double* a = r.a.data() + j.idx_v;
    const double* xd = full ? r.xd.data() + j.idx_v : nullptr;
    const double* xdd = r.xdd.data() + j.idx_v;
    if (j.type == mbk::JointType::kBall123) {
      angles_123_to_spherical(x, xd, xdd, q, v, a);
    } else if (j.type == mbk::JointType::kFree123) {
      Eigen::Map<Eigen::Vector3d> translation(q), linear(v), linear_dot(a);
      translation = Eigen::Map<const Eigen::Vector3d>(x);
      angles_123_to_spherical(x + 3, xd ? xd + 3 : nullptr, xdd + 3, q + 3, v + 3, a + 3);
      if (!full) continue;
      const Eigen::Matrix3d rt = Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(q + 3))
                                     .toRotationMatrix()
                                     .transpose();
      linear = rt * Eigen::Map<const Eigen::Vector3d>(xd);
      linear_dot = rt * Eigen::Map<const Eigen::Vector3d>(xdd) -
                   Eigen::Map<const Eigen::Vector3d>(v + 3).cross(linear);
    } else {
      if (j.cos_sin) {
        q[0] = std::cos(x[0]);
        q[1] = std::sin(x[0]);
      } else {
        q[0] = x[0];
      }
      if (!full) continue;
      v[0] = xd[0];
      a[0] = xdd[0];
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

// Pinocchio's bodies at the run's state (check_agreement).
std::vector<PeerBody> bodies_of(PinRun& r) {
  to_configuration(r, true);
  pinocchio::forwardKinematics(r.model, *r.data, r.q, r.v, r.a);
  mass_center_kinematics(r);
  std::vector<PeerBody> bodies;
  for (size_t n = 0; n < r.joints.size(); ++n) {
    const int i = static_cast<int>(n) + 1;
    bodies.push_back({r.joints[n].body, r.data->oMi[i].rotation(), r.p[i], r.omega[i], r.alpha[i],
                      r.vel[i], r.acc[i]});
  }
  return bodies;
}

}  // namespace

void register_pinocchio(const Scene& scene) {
  std::shared_ptr<PinRun> r = make_run(scene);
  check_agreement(scene, "Pinocchio", bodies_of(*r));
  const double bodies = static_cast<double>(r->joints.size());
  benchmark::RegisterBenchmark(("pinocchio/" + scene.name + "/pose").c_str(),
                               [r, bodies](benchmark::State& st) {
                                 int64_t i = 0;
                                 for (auto _ : st) {
                                   nudge(r->x.data(), nullptr, r->model.nv, i++);
                                   to_configuration(*r, false);
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
          nudge(r->x.data(), r->xd.data(), r->model.nv, i++);
          to_configuration(*r, true);
          pinocchio::forwardKinematics(r->model, *r->data, r->q, r->v, r->a);
          mass_center_kinematics(*r);
          benchmark::DoNotOptimize(r->acc.back().data());
          benchmark::ClobberMemory();
        }
        st.counters["bodies"] = bodies;
      });
  // The same without the conversion: Pinocchio given its own q, v and a (doc/speed.md).
  benchmark::RegisterBenchmark(("pinocchio/" + scene.name + "/full_own_coordinates").c_str(),
                               [r, bodies](benchmark::State& st) {
                                 to_configuration(*r, true);
                                 int64_t i = 0;
                                 for (auto _ : st) {
                                   nudge(r->q.data(), r->v.data(), r->model.nv, i++);
                                   pinocchio::forwardKinematics(r->model, *r->data, r->q, r->v,
                                                                r->a);
                                   mass_center_kinematics(*r);
                                   benchmark::DoNotOptimize(r->acc.back().data());
                                   benchmark::ClobberMemory();
                                 }
                                 st.counters["bodies"] = bodies;
                               });
}

}  // namespace mbk_bench
