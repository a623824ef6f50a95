// Closed forms (doc/method.md 6): single and double pendulum, a spinning top on 1-2-3 angles, and
// slider-hinge chains, against both formulations (doc/method.md 4 and 5).
//
// Tolerance: kTol = 1e-14 relative to each quantity's natural scale (the sum of the magnitudes of
// the closed form's terms, e.g. l1 |th1'| + c2 |phi'| for a velocity). Every value is a few
// (< 30) correctly rounded operations on O(1) inputs, so both sides carry a few ulp (2.2e-16)
// of that scale; 1e-14 leaves a margin of ~10 without hiding a wrong term, which would be O(1).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "test/support/checks.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;

constexpr double kTol = 1e-14;
constexpr int kStates = 25;  // random states per closed form

// Expected kinematics of one body, and the scales the tolerance is relative to.
struct Expected {
  M rotation;
  V origin, mass_center, omega, alpha, velocity, acceleration, origin_velocity, origin_acceleration;
  double length = 1, rate = 1, accel = 1;  // scales: positions, velocities, accelerations
  double spin = 1, spin_accel = 1;         // scales: omega, alpha
};

void expect_close(const V& actual, const V& expected, double scale, const std::string& what) {
  EXPECT_LE((actual - expected).norm(), kTol * scale)
      << what << "\n actual   " << actual.transpose() << "\n expected " << expected.transpose();
}

// Checks body k of `data` against the closed form.
void expect_body(const mbk::Data<double>& data, int k, const Expected& e, const std::string& tag) {
  const std::string at = tag + " body " + std::to_string(k) + ": ";
  EXPECT_LE((data.rotation[k] - e.rotation).norm(), kTol) << at << "S0K";
  expect_close(data.origin[k], e.origin, e.length, at + "origin");
  expect_close(data.mass_center[k], e.mass_center, e.length, at + "mass center");
  expect_close(data.omega[k], e.omega, e.spin, at + "omega");
  expect_close(data.alpha[k], e.alpha, e.spin_accel, at + "alpha");
  expect_close(data.origin_velocity[k], e.origin_velocity, e.rate, at + "origin velocity");
  expect_close(data.mass_center_velocity[k], e.velocity, e.rate, at + "velocity");
  expect_close(data.origin_acceleration[k], e.origin_acceleration, e.accel,
               at + "origin acceleration");
  expect_close(data.mass_center_acceleration[k], e.acceleration, e.accel, at + "acceleration");
}

// Runs both formulations on `state` and checks body k of each against `e`.
void expect_both(const mbk::Model& model, const mbk::JointState<double>& state, int k,
                 const Expected& e) {
  mbk_test::BothFormulations both(model);
  both.run(model, state);
  expect_body(both.recursive, k, e, "recursive (method.md 4)");
  expect_body(both.partial, k, e, "partial velocities (method.md 5)");
}

// A random state with every coordinate, speed and speed derivative in [-2, 2].
mbk::JointState<double> random_state(const mbk::Model& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  mbk::JointState<double> state(model);
  for (int i = 0; i < model.nq; ++i) state.position[i] = u(rng);
  for (int i = 0; i < model.nv; ++i) {
    state.velocity[i] = u(rng);
    state.acceleration[i] = u(rng);
  }
  return state;
}

mbk::Body make_body(const std::string& name, int lower, mbk::JointType type, const V& axis,
                    const V& offset, const V& mass_center) {
  mbk::Body body;
  body.name = name;
  body.lower = lower;
  body.joint.name = name + "_joint";
  body.joint.type = type;
  body.joint.axis = axis;
  body.joint.offset = offset;
  body.mass_center = mass_center;
  body.mass = 1.0;
  return body;
}

mbk::Model make_model(const std::vector<mbk::Body>& bodies) {
  mbk::Model model;
  model.bodies.resize(1);
  model.bodies.insert(model.bodies.end(), bodies.begin(), bodies.end());
  mbk::finalize_model(model);
  return model;
}

// Planar unit vectors along and across a link at angle th from x.
V radial(double th) { return V(std::cos(th), std::sin(th), 0.0); }
V tangential(double th) { return V(-std::sin(th), std::cos(th), 0.0); }
M rot_z(double th) {
  M r;
  r << std::cos(th), -std::sin(th), 0, std::sin(th), std::cos(th), 0, 0, 0, 1;
  return r;
}

// A point at distance c along a link at angle th (rate thd, angular acceleration thdd) from a
// fixed point: position c e_r, velocity c th' e_t, acceleration c (th'' e_t - th'^2 e_r).
struct LinkPoint {
  V p, v, a;
};
LinkPoint link_point(double c, double th, double thd, double thdd) {
  return {c * radial(th), c * thd * tangential(th),
          c * (thdd * tangential(th) - thd * thd * radial(th))};
}

// ---- Single pendulum: B1 on a hinge about z at O, mass center at distance c along x.
TEST(ClosedForm, SinglePendulum) {
  const double c = 0.7;
  const mbk::Model model = make_model(
      {make_body("link", 0, mbk::JointType::kRevolute, V::UnitZ(), V::Zero(), V(c, 0, 0))});
  std::mt19937 rng(1);
  for (int n = 0; n < kStates; ++n) {
    const mbk::JointState<double> s = random_state(model, rng);
    const double th = s.position[0], thd = s.velocity[0], thdd = s.acceleration[0];
    const LinkPoint g = link_point(c, th, thd, thdd);
    Expected e;
    e.rotation = rot_z(th);
    e.origin = e.origin_velocity = e.origin_acceleration = V::Zero();
    e.mass_center = g.p;
    e.velocity = g.v;
    e.acceleration = g.a;
    e.omega = thd * V::UnitZ();
    e.alpha = thdd * V::UnitZ();
    e.length = c;
    e.rate = c * std::abs(thd);
    e.accel = c * (std::abs(thdd) + thd * thd);
    e.spin = std::abs(thd);
    e.spin_accel = std::abs(thdd);
    expect_both(model, s, 1, e);
  }
}

// ---- Double pendulum: B2 hinged about z at distance l1 along B1's x; relative angles th1,
// th2, absolute angle of B2 phi = th1 + th2.
TEST(ClosedForm, DoublePendulum) {
  const double l1 = 1.3, c1 = 0.6, c2 = 0.45;
  const mbk::Model model = make_model(
      {make_body("upper", 0, mbk::JointType::kRevolute, V::UnitZ(), V::Zero(), V(c1, 0, 0)),
       make_body("lower", 1, mbk::JointType::kRevolute, V::UnitZ(), V(l1, 0, 0), V(c2, 0, 0))});
  std::mt19937 rng(2);
  for (int n = 0; n < kStates; ++n) {
    const mbk::JointState<double> s = random_state(model, rng);
    const double th1 = s.position[0], th1d = s.velocity[0], th1dd = s.acceleration[0];
    const double phi = th1 + s.position[1], phid = th1d + s.velocity[1],
                 phidd = th1dd + s.acceleration[1];
    const LinkPoint o2 = link_point(l1, th1, th1d, th1dd), g2 = link_point(c2, phi, phid, phidd);
    Expected e;
    e.rotation = rot_z(phi);
    e.origin = o2.p;
    e.origin_velocity = o2.v;
    e.origin_acceleration = o2.a;
    e.mass_center = o2.p + g2.p;
    e.velocity = o2.v + g2.v;
    e.acceleration = o2.a + g2.a;
    e.omega = phid * V::UnitZ();
    e.alpha = phidd * V::UnitZ();
    e.length = l1 + c2;
    e.rate = l1 * std::abs(th1d) + c2 * std::abs(phid);
    e.accel = l1 * (std::abs(th1dd) + th1d * th1d) + c2 * (std::abs(phidd) + phid * phid);
    e.spin = std::abs(th1d) + std::abs(s.velocity[1]);
    e.spin_accel = std::abs(th1dd) + std::abs(s.acceleration[1]);
    expect_both(model, s, 2, e);

    // B1 is the single pendulum.
    const LinkPoint g1 = link_point(c1, th1, th1d, th1dd);
    Expected e1 = e;
    e1.rotation = rot_z(th1);
    e1.origin = e1.origin_velocity = e1.origin_acceleration = V::Zero();
    e1.mass_center = g1.p;
    e1.velocity = g1.v;
    e1.acceleration = g1.a;
    e1.omega = th1d * V::UnitZ();
    e1.alpha = th1dd * V::UnitZ();
    expect_both(model, s, 1, e1);
  }
}

// ---- Spinning top on 1-2-3 angles. Written independently of doc/method.md 4's columns: the motion
// is X(alpha) Y(beta) Z(gamma) from Eigen's elementary rotations; their derivatives are
// d/dt R_u(th) = th' [u]x R_u and d2/dt2 R_u(th) = (th'' [u]x + th'^2 [u]x^2) R_u; S = C X Y Z by
// the product rule; omega from the skew part of S' S^T, alpha from the skew part of S'' S^T
// (the rest of d/dt(S' S^T) = S'' S^T + S' S'^T is symmetric); G = q + S r, v = S' r, a = S'' r.
struct Elementary {
  M r, d, dd;  // R_u(th) and its first and second time derivatives
};

Elementary elementary(const V& u, double th, double thd, double thdd) {
  const M k = mbk::skew(u);
  const M r = Eigen::AngleAxisd(th, u).toRotationMatrix();
  return {r, thd * k * r, (thdd * k + thd * thd * k * k) * r};
}

TEST(ClosedForm, SpinningTop123) {
  const V pivot(0.1, -0.2, 0.3), r(0.05, -0.1, 0.8);
  mbk::Body top = make_body("top", 0, mbk::JointType::kBall123, V::UnitZ(), pivot, r);
  const M c = Eigen::AngleAxisd(0.4, V(1, 2, 3).normalized()).toRotationMatrix();
  top.joint.rotation = c;  // a tilted pivot: SJK = C_k R_motion (doc/method.md 2)
  const mbk::Model model = make_model({top});
  std::mt19937 rng(3);
  for (int n = 0; n < kStates; ++n) {
    const mbk::JointState<double> s = random_state(model, rng);
    const auto& q = s.position;
    const auto& qd = s.velocity;
    const auto& qdd = s.acceleration;
    const Elementary x = elementary(V::UnitX(), q[0], qd[0], qdd[0]);
    const Elementary y = elementary(V::UnitY(), q[1], qd[1], qdd[1]);
    const Elementary z = elementary(V::UnitZ(), q[2], qd[2], qdd[2]);
    const M rot = c * x.r * y.r * z.r;
    const M rot_d = c * (x.d * y.r * z.r + x.r * y.d * z.r + x.r * y.r * z.d);
    const M rot_dd = c * (x.dd * y.r * z.r + x.r * y.dd * z.r + x.r * y.r * z.dd +
                          2.0 * (x.d * y.d * z.r + x.d * y.r * z.d + x.r * y.d * z.d));
    Expected e;
    e.rotation = rot;
    e.origin = pivot;
    e.origin_velocity = e.origin_acceleration = V::Zero();
    e.mass_center = pivot + rot * r;
    e.omega = mbk_test::vee_of_skew_part(rot_d * rot.transpose());
    e.alpha = mbk_test::vee_of_skew_part(rot_dd * rot.transpose());
    e.velocity = rot_d * r;
    e.acceleration = rot_dd * r;
    const double rates = qd.cwiseAbs().sum(), accels = qdd.cwiseAbs().sum();
    e.length = pivot.norm() + r.norm();
    e.spin = rates;
    e.spin_accel = accels + rates * rates;
    e.rate = r.norm() * e.spin;
    e.accel = r.norm() * e.spin_accel;
    expect_both(model, s, 1, e);
  }
}

// 1-2-3 angles equal three hinges about x, then the new y, then the new z (doc/method.md 2).
TEST(ClosedForm, Ball123EqualsThreeHinges) {
  const V pivot(0.1, -0.2, 0.3), r(0.05, -0.1, 0.8);
  const mbk::Model ball =
      make_model({make_body("ball", 0, mbk::JointType::kBall123, V::UnitZ(), pivot, r)});
  const mbk::Model hinges = make_model(
      {make_body("gimbal_x", 0, mbk::JointType::kRevolute, V::UnitX(), pivot, V::Zero()),
       make_body("gimbal_y", 1, mbk::JointType::kRevolute, V::UnitY(), V::Zero(), V::Zero()),
       make_body("top", 2, mbk::JointType::kRevolute, V::UnitZ(), V::Zero(), r)});
  std::mt19937 rng(4);
  for (int n = 0; n < kStates; ++n) {
    const mbk::JointState<double> s = random_state(ball, rng);  // same nq = nv = 3
    mbk_test::BothFormulations hinge_result(hinges);
    hinge_result.run(hinges, s);
    const mbk::Data<double>& h = hinge_result.recursive;
    Expected e;
    e.rotation = h.rotation[3];
    e.origin = h.origin[3];
    e.mass_center = h.mass_center[3];
    e.omega = h.omega[3];
    e.alpha = h.alpha[3];
    e.velocity = h.mass_center_velocity[3];
    e.acceleration = h.mass_center_acceleration[3];
    e.origin_velocity = h.origin_velocity[3];
    e.origin_acceleration = h.origin_acceleration[3];
    const double rates = s.velocity.cwiseAbs().sum();
    e.length = pivot.norm() + r.norm();
    e.spin = rates;
    e.spin_accel = s.acceleration.cwiseAbs().sum() + rates * rates;
    e.rate = r.norm() * e.spin;
    e.accel = r.norm() * e.spin_accel;
    expect_both(ball, s, 1, e);
  }
}

// ---- Slider then hinge (a cart-pole): B1 slides along x at height h; B2 is hinged about z at
// distance b along B1's x, its mass center at distance c along its own x.
TEST(ClosedForm, SliderThenHinge) {
  const double h = 0.4, b = 0.3, c = 0.9;
  const V r1(0.1, 0.2, 0.0);
  const mbk::Model model = make_model(
      {make_body("cart", 0, mbk::JointType::kPrismatic, V::UnitX(), V(0, h, 0), r1),
       make_body("pole", 1, mbk::JointType::kRevolute, V::UnitZ(), V(b, 0, 0), V(c, 0, 0))});
  std::mt19937 rng(5);
  for (int n = 0; n < kStates; ++n) {
    const mbk::JointState<double> s = random_state(model, rng);
    const double x = s.position[0], xd = s.velocity[0], xdd = s.acceleration[0];
    const double th = s.position[1], thd = s.velocity[1], thdd = s.acceleration[1];
    const LinkPoint g = link_point(c, th, thd, thdd);
    Expected cart;
    cart.rotation = M::Identity();
    cart.origin = V(x, h, 0);
    cart.mass_center = cart.origin + r1;
    cart.origin_velocity = cart.velocity = V(xd, 0, 0);
    cart.origin_acceleration = cart.acceleration = V(xdd, 0, 0);
    cart.omega = cart.alpha = V::Zero();
    cart.length = std::abs(x) + h + b + c + r1.norm();
    cart.rate = std::abs(xd) + c * std::abs(thd);
    cart.accel = std::abs(xdd) + c * (std::abs(thdd) + thd * thd);
    cart.spin = std::abs(thd);
    cart.spin_accel = std::abs(thdd);
    expect_both(model, s, 1, cart);

    Expected pole = cart;
    pole.rotation = rot_z(th);
    pole.origin = V(x + b, h, 0);
    pole.mass_center = pole.origin + g.p;
    pole.velocity = V(xd, 0, 0) + g.v;
    pole.acceleration = V(xdd, 0, 0) + g.a;
    pole.omega = thd * V::UnitZ();
    pole.alpha = thdd * V::UnitZ();
    expect_both(model, s, 2, pole);
  }
}

// ---- Hinge then slider (a telescoping arm, slider-crank-like): B2 slides along B1's x, which
// turns about z. With distance rho = s + c of G2 from the hinge:
// v = s' e_r + rho th' e_t, a = (s'' - rho th'^2) e_r + (rho th'' + 2 s' th') e_t (Coriolis).
TEST(ClosedForm, HingeThenSlider) {
  const double c = 0.35;
  const mbk::Model model = make_model(
      {make_body("arm", 0, mbk::JointType::kRevolute, V::UnitZ(), V::Zero(), V::Zero()),
       make_body("slide", 1, mbk::JointType::kPrismatic, V::UnitX(), V::Zero(), V(c, 0, 0))});
  std::mt19937 rng(6);
  for (int n = 0; n < kStates; ++n) {
    const mbk::JointState<double> s = random_state(model, rng);
    const double th = s.position[0], thd = s.velocity[0], thdd = s.acceleration[0];
    const double x = s.position[1], xd = s.velocity[1], xdd = s.acceleration[1];
    const V er = radial(th), et = tangential(th);
    Expected e;
    e.rotation = rot_z(th);
    e.omega = thd * V::UnitZ();
    e.alpha = thdd * V::UnitZ();
    e.origin = x * er;
    e.origin_velocity = xd * er + x * thd * et;
    e.origin_acceleration = (xdd - x * thd * thd) * er + (x * thdd + 2 * xd * thd) * et;
    const double rho = x + c;
    e.mass_center = rho * er;
    e.velocity = xd * er + rho * thd * et;
    e.acceleration = (xdd - rho * thd * thd) * er + (rho * thdd + 2 * xd * thd) * et;
    const double len = std::abs(x) + c;
    e.length = len;
    e.rate = std::abs(xd) + len * std::abs(thd);
    e.accel = std::abs(xdd) + len * (thd * thd + std::abs(thdd)) + 2 * std::abs(xd * thd);
    e.spin = std::abs(thd);
    e.spin_accel = std::abs(thdd);
    expect_both(model, s, 2, e);
  }
}

}  // namespace
