// Ball and free joints in any of the 12 Euler orders (Joint::euler_order, euler_order.h): on
// random trees mixing the orders (ball and free joints, random C_k, offsets and mass centers),
// the orientations are the three turns about the order's axes, velocities and accelerations are
// the time derivatives of positions and velocities at every level and in both formulations, and
// the double recursion agrees with the quad-precision reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/kinematics_error.h"
#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/analysis/reference_kinematics.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using D = mbk::Data<double>;
using mbk::EulerOrder;

constexpr int kOrders = static_cast<int>(EulerOrder::kLast) + 1;

// A random tree of n bodies on ball and free joints whose orders cycle through all 12 from
// `first` (so every order appears, mixed in one tree); C_k = I on every fifth body (the kernels'
// S0J P column shuffle), random elsewhere (C_k P folded at load).
mbk::Model ordered_tree(int n, unsigned seed, int first = 0) {
  mbk::Model model = mbk::make_random_tree(n, seed);
  for (int k = 1; k <= n; ++k) {
    mbk::Joint& joint = model.bodies[k].joint;
    joint.type = (k + seed) % 3 ? mbk::JointType::kBall123 : mbk::JointType::kFree123;
    joint.euler_order = static_cast<EulerOrder>((first + k) % kOrders);
    if (k % 5 == 0) joint.rotation.setIdentity();
  }
  mbk::finalize_model(model);
  return model;
}

// The three turns of body k's joint about its order's axes, and C_k: S0K = S0J C_k R R R.
mbk::Mat3<double> expected_sjk(const mbk::Joint& joint, const double* angles) {
  const std::array<int, 3> a = mbk::euler_axes(joint.euler_order);
  mbk::Mat3<double> r = joint.rotation;
  for (int i = 0; i < 3; ++i)
    r = r * Eigen::AngleAxisd(angles[i], V::Unit(a[i])).toRotationMatrix();
  return r;
}

TEST(EulerOrders, OrientationsAreTheTurnsAboutEachOrdersAxes) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = ordered_tree(24, seed);
    std::mt19937 rng(seed);
    const mbk::JointState<double> state = mbk::random_state(model, rng);
    D data(model);
    mbk::forward_kinematics(model, state, data, mbk::Level::kPose);
    for (int k = 1; k <= model.body_count(); ++k) {
      const mbk::Body& body = model.bodies[k];
      const int t = mbk::translation_count(body.joint.type);
      const mbk::Mat3<double> s0k =
          data.rotation[body.lower] *
          expected_sjk(body.joint, state.position.data() + body.q_index + t);
      EXPECT_LT((data.rotation[k] - s0k).norm(), 1e-13)
          << "seed " << seed << " body " << k << " " << mbk::to_string(body.joint.euler_order);
    }
  }
}

// Fourth-order central differences with h = 5e-4, as finite_difference_test (its kFdTol).
constexpr double kH = 5e-4, kFdTol = 1e-10;

// forward_kinematics at `level` and partial_velocity_kinematics, into two Data.
void both(const mbk::Model& model, const mbk::JointState<double>& state, mbk::Level level, D& fk,
          D& pvk) {
  mbk::PartialVelocities<double> pv(model);
  mbk::forward_kinematics(model, state, fk, level);
  mbk::partial_velocity_kinematics(model, state, pv, pvk, level);
}

// Body k's derivative pairs at a level: (rotation -> omega via W = S' S^T is checked apart).
void expect_derivatives(const mbk::Model& model, const mbk_test::Trajectory& trajectory, double t,
                        mbk::Level level, const std::string& where) {
  const mbk::Level below =
      level == mbk::Level::kVelocity ? mbk::Level::kPose : mbk::Level::kVelocity;
  D at(model), at_pv(model);
  both(model, trajectory.at<double>(t), level, at, at_pv);
  std::vector<D> samples, samples_pv;
  for (double offset : mbk_test::kStencilOffsets) {
    samples.emplace_back(model);
    samples_pv.emplace_back(model);
    both(model, trajectory.at<double>(t + offset * kH), below, samples.back(), samples_pv.back());
  }
  using Pair = std::pair<std::vector<V> D::*, std::vector<V> D::*>;
  const std::vector<Pair> pairs =
      level == mbk::Level::kVelocity
          ? std::vector<Pair>{{&D::mass_center, &D::mass_center_velocity},
                              {&D::origin, &D::origin_velocity}}
          : std::vector<Pair>{{&D::mass_center_velocity, &D::mass_center_acceleration},
                              {&D::origin_velocity, &D::origin_acceleration},
                              {&D::omega, &D::alpha}};
  for (const std::vector<D>* s : {&samples, &samples_pv})
    for (int k = 1; k <= model.body_count(); ++k) {
      for (auto [f, df] : pairs) {
        const V fd = mbk_test::central_difference<V>([&](int i) { return ((*s)[i].*f)[k]; }, kH);
        for (const D* exact_data : {&at, &at_pv}) {
          const V exact = (exact_data->*df)[k];
          const double scale = std::max({1.0, (at.*f)[k].norm(), exact.norm()});
          EXPECT_LE((fd - exact).norm(), kFdTol * scale) << where << " body " << k;
        }
      }
      if (level != mbk::Level::kVelocity) continue;
      const mbk::Mat3<double> sd = mbk_test::central_difference<mbk::Mat3<double>>(
          [&](int i) { return (*s)[i].rotation[k]; }, kH);
      const V omega = mbk_test::vee_of_skew_part(sd * at.rotation[k].transpose());
      for (const D* exact_data : {&at, &at_pv})
        EXPECT_LE((omega - exact_data->omega[k]).norm(),
                  kFdTol * std::max(1.0, exact_data->omega[k].norm()))
            << where << " omega of body " << k;
    }
}

TEST(EulerOrders, DerivativesAreFiniteDifferencesAtEveryLevel) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = ordered_tree(14, seed, static_cast<int>(seed));
    const mbk_test::Trajectory trajectory(model, seed + 100);
    for (double t : {0.0, 0.73, 2.9})
      for (mbk::Level level : {mbk::Level::kVelocity, mbk::Level::kAcceleration})
        expect_derivatives(model, trajectory, t, level,
                           "seed " + std::to_string(seed) + " t " + std::to_string(t));
  }
}

// Double against quad on the same inputs: ~depth * eps relative (finite_difference_test's
// kLongDoubleTol, 1e-13); a wrong term would be O(1).
TEST(EulerOrders, DoubleAgreesWithQuadReference) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = ordered_tree(30, seed);
    std::mt19937 rng(seed);
    const mbk::JointState<double> state = mbk::random_state(model, rng);
    for (mbk::Level level : {mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration}) {
      mbk::Data<mbk::Quad> reference(model);
      mbk::forward_kinematics(model, mbk::cast_state<mbk::Quad>(model, state), reference, level);
      D data(model), pvk(model);
      both(model, state, level, data, pvk);
      EXPECT_LT(mbk::kinematics_error(data, reference, level).max(), 1e-13) << "seed " << seed;
      EXPECT_LT(mbk::kinematics_error(pvk, reference, level).max(), 1e-13) << "seed " << seed;
    }
  }
}

}  // namespace
