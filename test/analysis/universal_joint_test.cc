// The universal joint (JointType::kUniversal, added in joint.h, joint.cc and joint_motion.h
// only): on trees of universal joints with random C_k, offsets and mass centers, its velocities
// and accelerations are the time derivatives of its positions and velocities, and the double
// recursion agrees with the quad-precision reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/kinematics_error.h"
#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/analysis/reference_kinematics.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using D = mbk::Data<double>;

mbk::Model universal_tree(int n, unsigned seed) {
  mbk::Model model = mbk::make_random_tree(n, seed);
  for (int k = 1; k <= n; ++k) model.bodies[k].joint.type = mbk::JointType::kUniversal;
  mbk::finalize_model(model);
  return model;
}

// Fourth-order central differences with h = 5e-4, as finite_difference_test (its kFdTol).
constexpr double kH = 5e-4, kFdTol = 1e-10;

TEST(UniversalJoint, DerivativesAreFiniteDifferences) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = universal_tree(12, seed);
    const mbk_test::Trajectory trajectory(model, seed + 100);
    for (double t : {0.0, 0.73, 2.9}) {
      D at(model);
      mbk::forward_kinematics(model, trajectory.at<double>(t), at);
      std::vector<D> samples;
      for (double offset : mbk_test::kStencilOffsets) {
        samples.emplace_back(model);
        mbk::forward_kinematics(model, trajectory.at<double>(t + offset * kH), samples.back());
      }
      for (int k = 1; k <= model.body_count(); ++k)
        for (auto [f, df] : {std::pair{&D::mass_center, &D::mass_center_velocity},
                             std::pair{&D::mass_center_velocity, &D::mass_center_acceleration},
                             std::pair{&D::omega, &D::alpha}}) {
          const V fd =
              mbk_test::central_difference<V>([&](int i) { return (samples[i].*f)[k]; }, kH);
          const V exact = (at.*df)[k];
          const double scale = std::max({1.0, (at.*f)[k].norm(), exact.norm()});
          EXPECT_LE((fd - exact).norm(), kFdTol * scale)
              << "seed " << seed << " t " << t << " body " << k;
        }
    }
  }
}

// Double against quad on the same inputs: ~depth * eps relative (finite_difference_test's
// kLongDoubleTol, 1e-13); a wrong term would be O(1).
TEST(UniversalJoint, DoubleAgreesWithQuadReference) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = universal_tree(30, seed);
    std::mt19937 rng(seed);
    const mbk::JointState<double> state = mbk::random_state(model, rng);
    mbk::Data<mbk::Quad> reference(model);
    mbk::forward_kinematics(model, mbk::cast_state<mbk::Quad>(model, state), reference);
    D data(model);
    mbk::forward_kinematics(model, state, data);
    EXPECT_LT(mbk::kinematics_error(data, reference).max(), 1e-13) << "seed " << seed;
  }
}

}  // namespace
