// Segment frames and joint motion (core/segment_frames.h, doc/method.md 10): closed forms of a
// double pendulum in the bodies' own axes; on random trees of every joint type, the relative
// rotation's and relative angular velocity's time derivatives (central differences) against
// relative_omega and relative_alpha; and a revolute joint's relative motion C_k n q', C_k n q''
// on a moving lower body.
#include "mb_kinematics/core/segment_frames.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;

// Closed forms: a few correctly rounded operations on O(1) values (as closed_form_test.cc).
constexpr double kTol = 1e-14;
// Central differences, h = 5e-4 (as finite_difference_test.cc, whose bound holds here: the
// relative quantities are differences of the absolute ones it checks): 1e-10 relative to
// max(1, |f|, |f'|).
constexpr double kH = 5e-4;
constexpr double kFdTol = 1e-10;

mbk::Body revolute_body(const std::string& name, int lower, const V& offset, const V& g) {
  mbk::Body body;
  body.name = name;
  body.lower = lower;
  body.joint.name = name + "_joint";
  body.joint.type = mbk::JointType::kRevolute;
  body.joint.axis = V::UnitZ();
  body.joint.offset = offset;
  body.mass_center = g;
  body.mass = 1.0;
  return body;
}

// Double pendulum about z: B1 at O, B2 at l1 along B1's x, mass centers c1, c2 along their x.
// In B2's own axes (absolute angle phi = th1 + th2, relative th2): omega = phi' z, alpha = phi''
// z; the velocity of G2 = l1 th1' (sin th2 x + cos th2 y) + c2 phi' y; its acceleration
// l1 (th1'' sin th2 - th1'^2 cos th2) x + l1 (th1'' cos th2 + th1'^2 sin th2) y
// + c2 (phi'' y - phi'^2 x). Relative to B1: rotation R_z(th2), omega th2' z, alpha th2'' z.
TEST(SegmentFrames, DoublePendulumClosedForm) {
  const double l1 = 1.3, c1 = 0.6, c2 = 0.45;
  mbk::Model model;
  model.bodies.resize(1);
  model.bodies.push_back(revolute_body("upper", 0, V::Zero(), V(c1, 0, 0)));
  model.bodies.push_back(revolute_body("lower", 1, V(l1, 0, 0), V(c2, 0, 0)));
  mbk::finalize_model(model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int n = 0; n < 25; ++n) {
    mbk::JointState<double> s(model);
    for (int i = 0; i < 2; ++i)
      s.position[i] = u(rng), s.velocity[i] = u(rng), s.acceleration[i] = u(rng);
    mbk::Data<double> d(model);
    mbk::forward_kinematics(model, s, d);
    const double th2 = s.position[1], w1 = s.velocity[0], a1 = s.acceleration[0];
    const double w = w1 + s.velocity[1], a = a1 + s.acceleration[1];
    const double c = std::cos(th2), sn = std::sin(th2);
    const V v(l1 * w1 * sn, l1 * w1 * c + c2 * w, 0);
    const V acc(l1 * (a1 * sn - w1 * w1 * c) - c2 * w * w, l1 * (a1 * c + w1 * w1 * sn) + c2 * a,
                0);
    const double scale = l1 * (std::abs(a1) + w1 * w1) + c2 * (std::abs(a) + w * w);
    EXPECT_LE((mbk::in_body_axes(d, 2, d.omega[2]) - w * V::UnitZ()).norm(), kTol * std::abs(w));
    EXPECT_LE((mbk::in_body_axes(d, 2, d.alpha[2]) - a * V::UnitZ()).norm(), kTol * std::abs(a));
    EXPECT_LE((mbk::in_body_axes(d, 2, d.mass_center_velocity[2]) - v).norm(),
              kTol * (l1 * std::abs(w1) + c2 * std::abs(w)));
    EXPECT_LE((mbk::in_body_axes(d, 2, d.mass_center_acceleration[2]) - acc).norm(), kTol * scale);
    const mbk::RelativeMotion<double> m = mbk::relative_motion(model, d, 2);
    const M rz = Eigen::AngleAxisd(th2, V::UnitZ()).toRotationMatrix();
    EXPECT_LE((m.rotation - rz).norm(), kTol);
    EXPECT_LE((m.omega - s.velocity[1] * V::UnitZ()).norm(), kTol * (std::abs(w) + std::abs(w1)));
    EXPECT_LE((m.alpha - s.acceleration[1] * V::UnitZ()).norm(),
              kTol * (std::abs(a) + std::abs(a1) + w * w + w1 * w1));
  }
}

// SJK' = [w_rel] SJK in Bj's axes (w_rel = relative_omega), and relative_alpha = relative_omega'.
TEST(SegmentFrames, RelativeMotionIsTheDerivativeOfTheRelativeRotation) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const mbk::Model model = mbk_test::random_tree(13, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    for (double t : {0.0, 0.73, 2.9}) {
      std::vector<mbk::Data<double>> samples;
      for (double offset : mbk_test::kStencilOffsets) {
        samples.emplace_back(model);
        mbk::forward_kinematics(model, trajectory.at<double>(t + offset * kH), samples.back());
      }
      mbk::Data<double> at(model);
      mbk::forward_kinematics(model, trajectory.at<double>(t), at);
      for (int k = 1; k <= model.body_count(); ++k) {
        const std::string where = "seed " + std::to_string(seed) + " t " + std::to_string(t) +
                                  " body " + std::to_string(k) + ": ";
        const mbk::RelativeMotion<double> m = mbk::relative_motion(model, at, k);
        const M rd = mbk_test::central_difference<M>(
            [&](int i) { return mbk::relative_motion(model, samples[i], k).rotation; }, kH);
        const V w = mbk_test::vee_of_skew_part(rd * m.rotation.transpose());
        EXPECT_LE((w - m.omega).norm(), kFdTol * std::max(1.0, m.omega.norm()))
            << where << "relative omega";
        const V wd = mbk_test::central_difference<V>(
            [&](int i) { return mbk::relative_motion(model, samples[i], k).omega; }, kH);
        EXPECT_LE((wd - m.alpha).norm(), kFdTol * std::max({1.0, m.omega.norm(), m.alpha.norm()}))
            << where << "relative alpha";
      }
    }
  }
}

// A revolute body k (axis n in the joint frame, C_k) on any lower body: relative_omega = C_k n q'
// and relative_alpha = C_k n q'', whatever the lower body does.
TEST(SegmentFrames, RevoluteJointOnAMovingLowerBody) {
  int checked = 0;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    const mbk::Model model = mbk_test::random_tree(21, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    const mbk::JointState<double> s = trajectory.at<double>(1.1);
    mbk::Data<double> d(model);
    mbk::forward_kinematics(model, s, d);
    for (int k = 1; k <= model.body_count(); ++k) {
      const mbk::Body& b = model.bodies[k];
      if (b.joint.type != mbk::JointType::kRevolute || b.lower == 0) continue;
      const V n = b.joint.rotation * b.joint.axis.normalized();
      const double qd = s.velocity[b.v_index], qdd = s.acceleration[b.v_index];
      const mbk::RelativeMotion<double> m = mbk::relative_motion(model, d, k);
      const double spin = d.omega[k].norm() + d.omega[b.lower].norm();
      EXPECT_LE((m.omega - qd * n).norm(), 1e-13 * std::max(1.0, spin)) << "body " << k;
      EXPECT_LE((m.alpha - qdd * n).norm(),
                1e-13 * std::max(1.0, spin * spin + d.alpha[k].norm() + d.alpha[b.lower].norm()))
          << "body " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5);
}

}  // namespace
