// The work-precision harness itself: its quad-precision reference is more precise than double
// on a case with a known answer, the error measure does what it says, and the Euler-parameter
// variant of a state describes the same motion.
#include <gtest/gtest.h>

#include "mb_kinematics/analysis/kinematics_error.h"
#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/analysis/reference_kinematics.h"
#include "mb_kinematics/core/joint.h"

namespace {

using mbk::Quad;

// A planar chain of n hinges about z, unit links along x, every joint at theta: the origin of
// body k is sum_{i=1}^{k-1} (cos(i theta), sin(i theta), 0), in closed form with quad sines.
TEST(Reference, QuadIsMorePreciseThanDoubleOnAKnownAnswer) {
  const int n = 200;
  mbk::Model model = mbk::make_chain(n, mbk::JointType::kRevolute);
  for (int k = 1; k <= n; ++k) model.bodies[k].joint.axis = mbk::Vec3<double>::UnitZ();
  mbk::finalize_model(model);
  const double theta = 1.0 / 3;  // the same input for both runs
  mbk::JointState<Quad> quad_state(model);
  mbk::JointState<double> double_state(model);
  quad_state.position.setConstant(Quad(theta));
  double_state.position.setConstant(theta);
  mbk::Data<Quad> quad(model);
  mbk::Data<double> dbl(model);
  mbk::forward_kinematics(model, quad_state, quad, mbk::Level::kPose);
  mbk::forward_kinematics(model, double_state, dbl, mbk::Level::kPose);
  const Quad t = Quad(theta);
  Quad worst_quad = 0, worst_double = 0;
  for (int k = 2; k <= n; ++k) {
    Quad x = 0, y = 0;
    for (int i = 1; i < k; ++i) x += cos(i * t), y += sin(i * t);
    worst_quad =
        std::max(worst_quad, std::max(abs(quad.origin[k].x() - x), abs(quad.origin[k].y() - y)));
    worst_double = std::max(
        worst_double, std::max(abs(Quad(dbl.origin[k].x()) - x), abs(Quad(dbl.origin[k].y()) - y)));
  }
  // Quad rounding is 2^-113 ~ 1e-34 per operation; a 200-link sum of O(1) terms stays far
  // below 1e-28. Double's is 1.1e-16 per operation: it must show (> 1e-16 somewhere over 200
  // links) and stay below 200 links * 10 ulp.
  EXPECT_LT(static_cast<double>(worst_quad), 1e-28);
  EXPECT_GT(static_cast<double>(worst_double), 1e-16);
  EXPECT_LT(static_cast<double>(worst_double), 200 * 10 * 2.3e-16);
}

TEST(Reference, ErrorIsRelativeToEachQuantitysScale) {
  const mbk::Model model = mbk::make_chain(3, mbk::JointType::kRevolute);
  mbk::Data<double> a(model), b(model);
  for (int k = 1; k <= 3; ++k) {
    b.omega[k] = mbk::Vec3<double>(k, 0, 0);                             // scale of omega: 3
    b.mass_center_acceleration[k] = mbk::Vec3<double>(0, 100.0 * k, 0);  // scale: 300
  }
  a = b;
  a.omega[1].x() += 3e-10;                     // 1e-10 relative (1 + 3e-10 rounds by up to 1.1e-16)
  a.mass_center_acceleration[2].z() += 6e-12;  // 2e-14 relative (0 + 6e-12 is exact)
  const mbk::KinematicsError e = mbk::kinematics_error(a, b);
  EXPECT_NEAR(e.relative[mbk::ErrorQuantity::kOmega], 1e-10, 1.1e-16 / 3);
  EXPECT_NEAR(e.relative[mbk::ErrorQuantity::kAcceleration], 2e-14, 1e-26);
  EXPECT_EQ(e.relative[mbk::ErrorQuantity::kPosition], 0.0);
  EXPECT_EQ(e.max(), e.relative[mbk::ErrorQuantity::kOmega]);
}

// euler_state (used for the "Euler" rows of the report) converts 1-2-3 angle joints of a state
// into Euler parameters describing the same motion: in quad, every quantity agrees to rounding.
// Seeds 6 to 8: the angle joints in all 12 Euler orders (Joint::euler_order).
TEST(Reference, EulerStateDescribesTheSameMotion) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    mbk::Model model = mbk::make_random_tree(30, seed);
    for (int k = 1; k <= model.body_count() && seed > 5; ++k)
      model.bodies[k].joint.euler_order = static_cast<mbk::EulerOrder>(k % 12);
    mbk::finalize_model(model);
    std::mt19937 rng(seed);
    const mbk::JointState<double> state = mbk::random_state(model, rng);
    const mbk::JointState<Quad> exact = mbk::cast_state<Quad>(model, state);
    mbk::Data<Quad> reference(model), converted(model);
    mbk::forward_kinematics(model, exact, reference);
    for (mbk::SpeedKind speeds :
         {mbk::SpeedKind::kCoordinateDerivatives, mbk::SpeedKind::kAngularVelocity}) {
      const mbk::Model euler = mbk::with_euler_parameters(model, speeds);
      mbk::forward_kinematics(euler, mbk::euler_state(model, euler, exact), converted);
      // Quad rounding (1e-34) through ~30 bodies of O(1) terms: far below 1e-28; a wrong
      // conversion (sign, frame, factor 2) would be O(1).
      EXPECT_LT(mbk::kinematics_error(converted, reference).max(), 1e-28) << "seed " << seed;
    }
  }
}

}  // namespace
