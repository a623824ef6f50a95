// The fast kernels of the recursion (core/fast_kernels.h, the AVX2 copy included) are opt-in
// specializations of the generic path, joint_motion per body (JointKernel::kGeneric): for every
// joint type, with and without offset rotations, on random trees and random states, both
// formulations give what the generic path gives, to rounding.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "mb_kinematics/analysis/kinematics_error.h"
#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"

namespace {

using mbk::JointType;
using mbk::SpeedKind;

// Not bit for bit: a kernel folds C_k and the axis into its constants (P0 + c P1 + s P2) or
// turns two columns where joint_motion multiplies C_k R(q), so SJK differs by a few ulp, and the
// difference grows with depth as rounding does (README "Numerical stability"): about depth * 4
// eps relative to each quantity's scale, at most ~20 * 4 * 1.1e-16 ~ 1e-14 on these trees of 20
// bodies. A wrong term (a Coriolis term, a column, a frame) is O(1).
constexpr double kTol = 1e-13;

// A random tree of n bodies whose joints all have `type` (random axes, offsets and C_k).
mbk::Model tree_of(JointType type, unsigned seed, SpeedKind speeds) {
  mbk::Model model = mbk::make_random_tree(20, seed, speeds);
  for (int k = 1; k <= model.body_count(); ++k) model.bodies[k].joint.type = type;
  mbk::finalize_model(model);
  return model;
}

// The same model with every body on the generic path.
mbk::Model generic(const mbk::Model& model) {
  mbk::Model out = model;
  out.steps = mbk::make_body_steps(out, mbk::KernelChoice::kGenericOnly);
  return out;
}

void expect_same_kinematics(const mbk::Model& model, const std::string& where) {
  const mbk::Model reference = generic(model);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const mbk::JointState<double> state = mbk::random_state(model, rng);
    for (mbk::Level level : {mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration}) {
      mbk::Data<double> fast(model), slow(model), pv(model), pv_slow(model);
      mbk::forward_kinematics(model, state, fast, level);
      mbk::forward_kinematics(reference, state, slow, level);
      EXPECT_LT(mbk::kinematics_error(fast, slow, level).max(), kTol) << where << " recursion";
      mbk::PartialVelocities<double> p(model), p_slow(model);
      mbk::partial_velocity_kinematics(model, state, p, pv, level);
      mbk::partial_velocity_kinematics(reference, state, p_slow, pv_slow, level);
      EXPECT_LT(mbk::kinematics_error(pv, pv_slow, level).max(), kTol)
          << where << " partial velocities";
      EXPECT_LT(mbk::kinematics_error(pv_slow, slow, level).max(), kTol)
          << where << " formulations";
    }
  }
}

TEST(GenericKernel, EveryJointTypesKernelIsTheGenericPath) {
  for (JointType type : mbk::all_joint_types())
    for (SpeedKind speeds : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity})
      for (unsigned seed = 1; seed <= 3; ++seed)
        expect_same_kinematics(tree_of(type, seed, speeds),
                               mbk::to_string(type) + " seed " + std::to_string(seed));
}

TEST(GenericKernel, MixedTreesAreTheGenericPath) {
  for (unsigned seed = 1; seed <= 5; ++seed)
    expect_same_kinematics(mbk::make_random_tree(40, seed), "mixed seed " + std::to_string(seed));
}

// Ball and free joints in each of the 12 Euler orders (kBallOrdered, kFreeOrdered; kBall123 for
// XYZ), with and without C_k, and all orders mixed in one tree.
TEST(GenericKernel, EveryEulerOrdersKernelIsTheGenericPath) {
  constexpr int kOrders = static_cast<int>(mbk::EulerOrder::kLast) + 1;
  for (JointType type : {JointType::kBall123, JointType::kFree123})
    for (int order = 0; order <= kOrders; ++order)  // kOrders: all mixed
      for (bool rotated : {false, true}) {
        mbk::Model model = tree_of(type, 1, SpeedKind::kCoordinateDerivatives);
        for (int k = 1; k <= model.body_count(); ++k) {
          mbk::Joint& joint = model.bodies[k].joint;
          joint.euler_order = static_cast<mbk::EulerOrder>(order < kOrders ? order : k % kOrders);
          if (!rotated) joint.rotation.setIdentity();
        }
        mbk::finalize_model(model);
        expect_same_kinematics(model, mbk::to_string(type) + " order " + std::to_string(order) +
                                          (rotated ? " with C_k" : ""));
      }
}

// A model whose bodies all run joint_motion really does: every step is kGeneric.
TEST(GenericKernel, GenericOnlyPicksNoKernel) {
  const mbk::Model model = generic(mbk::make_random_tree(30, 1));
  for (int k = 1; k <= model.body_count(); ++k)
    EXPECT_EQ(model.steps.steps[k].kernel, mbk::JointKernel::kGeneric) << k;
}

}  // namespace
