// forward_kinematics and system_kinematics of four and of eight samples at once
// (core/kinematics_lanes.h): each lane is its sample's computation in double bit for bit, for every
// joint type's kernel and Euler order, both kinds of speeds, every level, mimic joints and trees
// deep enough to be reorthonormalized; lanes the CPU or the model does not take (a generic kernel)
// are told and refused.
#include "mb_kinematics/core/kinematics_lanes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/io/load_model.h"
#include "test/support/test_models.h"

namespace {

using mbk::DoubleLanes;
using mbk::JointType;
using mbk::Level;
using mbk::SpeedKind;

// Whether this build has the lanes (the AVX2 copy's dispatch: not in sanitizer builds) and this
// CPU runs N of them.
template <int N>
bool lanes_here() {
#ifdef MBK_AVX2_DISPATCH
  return N == 4 ? __builtin_cpu_supports("avx2") : __builtin_cpu_supports("avx512f");
#else
  return false;
#endif
}

bool has_generic_kernel(const mbk::Model& model) {
  for (int k = 1; k <= model.body_count(); ++k)
    if (model.steps.steps[k].kernel == mbk::JointKernel::kGeneric) return true;
  return false;
}

// N states of one smooth trajectory, far apart in time. A model with angular-velocity speeds
// takes it from `twin`, the same model with coordinate-derivative speeds.
std::vector<mbk::JointState<double>> states_of(const mbk::Model& model, const mbk::Model& twin,
                                               int n) {
  const mbk_test::Trajectory trajectory(twin, 5);
  std::vector<mbk::JointState<double>> states(n, mbk::JointState<double>(model));
  for (int l = 0; l < n; ++l) {
    const double t = 0.3 + 4.4 * l / (n - 1) + 0.05 * (l % 3);
    states[l] = model.speeds == SpeedKind::kAngularVelocity
                    ? mbk_test::state_with_angular_speeds(model, twin, trajectory, t)
                    : trajectory.at<double>(t);
    mbk::apply_mimics(model, states[l]);
  }
  return states;
}

template <int N>
mbk::JointState<DoubleLanes<N>> lanes_of(const mbk::Model& model,
                                         const std::vector<mbk::JointState<double>>& states) {
  mbk::JointState<DoubleLanes<N>> lanes(model);
  for (int l = 0; l < N; ++l) {
    for (int i = 0; i < model.nq; ++i) lanes.position[i].v[l] = states[l].position[i];
    for (int i = 0; i < model.nv; ++i) {
      lanes.velocity[i].v[l] = states[l].velocity[i];
      lanes.acceleration[i].v[l] = states[l].acceleration[i];
    }
  }
  return lanes;
}

// Bitwise: -0.0 and NaN patterns count.
template <int N>
void expect_bits(double expected, const DoubleLanes<N>& actual, int lane,
                 const std::string& where) {
  const double a = actual.v[lane];
  EXPECT_EQ(0, std::memcmp(&expected, &a, sizeof(double)))
      << where << " lane " << lane << ": " << expected << " vs " << a;
}

template <int N, int R, int C>
void expect_bits(const Eigen::Matrix<double, R, C>& expected,
                 const Eigen::Matrix<DoubleLanes<N>, R, C>& actual, int lane,
                 const std::string& where) {
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) expect_bits(expected(i, j), actual(i, j), lane, where);
}

template <int N>
void expect_lanes_are_samples(const mbk::Model& model, const std::string& where,
                              const mbk::Model* twin = nullptr) {
  using Lanes = DoubleLanes<N>;
  const bool runs = lanes_here<N>() && !has_generic_kernel(model);
  ASSERT_EQ(mbk::samples_at_once(model) >= N, runs) << where;
  const std::vector<mbk::JointState<double>> states = states_of(model, twin ? *twin : model, N);
  const mbk::JointState<Lanes> lanes = lanes_of<N>(model, states);
  if (!runs) {
    mbk::Data<Lanes> data(model);
    mbk::SystemKinematics<Lanes> system;
    EXPECT_THROW(mbk::forward_kinematics(model, lanes, data, Level::kPose), std::logic_error);
    EXPECT_THROW(mbk::system_kinematics(model, data, system, Level::kPose), std::logic_error);
    return;
  }
  for (const Level level : {Level::kPose, Level::kVelocity, Level::kAcceleration}) {
    const std::string at = where + " level " + std::to_string(static_cast<int>(level));
    mbk::Data<Lanes> data4(model);
    mbk::SystemKinematics<Lanes> system4;
    mbk::forward_kinematics(model, lanes, data4, level);
    mbk::system_kinematics(model, data4, system4, level);
    for (int l = 0; l < N; ++l) {
      mbk::Data<double> data(model);
      mbk::SystemKinematics<double> system;
      mbk::forward_kinematics(model, states[l], data, level);
      mbk::system_kinematics(model, data, system, level);
      for (int k = 1; k <= model.body_count(); ++k) {
        const std::string body = at + " body " + std::to_string(k);
        expect_bits(data.rotation[k], data4.rotation[k], l, body + " rotation");
        expect_bits(data.origin[k], data4.origin[k], l, body + " origin");
        expect_bits(data.mass_center[k], data4.mass_center[k], l, body + " mass center");
        expect_bits(data.omega[k], data4.omega[k], l, body + " omega");
        expect_bits(data.alpha[k], data4.alpha[k], l, body + " alpha");
        expect_bits(data.origin_velocity[k], data4.origin_velocity[k], l, body);
        expect_bits(data.origin_acceleration[k], data4.origin_acceleration[k], l, body);
        expect_bits(data.mass_center_velocity[k], data4.mass_center_velocity[k], l, body);
        expect_bits(data.mass_center_acceleration[k], data4.mass_center_acceleration[k], l, body);
      }
      expect_bits(system.mass, system4.mass, l, at + " system mass");
      EXPECT_EQ(system.has_mass, system4.has_mass) << at;
      EXPECT_EQ(system.angular_momentum_known, system4.angular_momentum_known) << at;
      expect_bits(system.mass_center, system4.mass_center, l, at + " system mass center");
      expect_bits(system.velocity, system4.velocity, l, at + " system velocity");
      expect_bits(system.acceleration, system4.acceleration, l, at + " system acceleration");
      expect_bits(system.linear_momentum, system4.linear_momentum, l, at + " linear momentum");
      expect_bits(system.angular_momentum, system4.angular_momentum, l, at + " H_G");
    }
  }
}

// A random tree of 20 bodies whose joints all have `type` (random axes, offsets and C_k).
mbk::Model tree_of(JointType type, unsigned seed, SpeedKind speeds) {
  mbk::Model model = mbk::make_random_tree(20, seed, speeds);
  for (int k = 1; k <= model.body_count(); ++k) model.bodies[k].joint.type = type;
  mbk::finalize_model(model);
  return model;
}

// Four lanes (AVX2) and eight (AVX-512F).
template <typename Lanes>
class SamplesInLanes : public testing::Test {};
using LaneCounts = testing::Types<std::integral_constant<int, 4>, std::integral_constant<int, 8>>;
TYPED_TEST_SUITE(SamplesInLanes, LaneCounts);

TYPED_TEST(SamplesInLanes, EveryJointTypesKernelLaneByLane) {
  for (JointType type : mbk::all_joint_types())
    for (SpeedKind speeds : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity}) {
      const mbk::Model twin = tree_of(type, 3, SpeedKind::kCoordinateDerivatives);
      expect_lanes_are_samples<TypeParam::value>(tree_of(type, 3, speeds), mbk::to_string(type),
                                                 &twin);
    }
}

TYPED_TEST(SamplesInLanes, EveryEulerOrderLaneByLane) {
  constexpr int kOrders = static_cast<int>(mbk::EulerOrder::kLast) + 1;
  for (JointType type : {JointType::kBall123, JointType::kFree123})
    for (int order = 0; order < kOrders; ++order) {
      mbk::Model model = tree_of(type, 2, SpeedKind::kCoordinateDerivatives);
      for (int k = 1; k <= model.body_count(); ++k)
        model.bodies[k].joint.euler_order = static_cast<mbk::EulerOrder>(order);
      mbk::finalize_model(model);
      expect_lanes_are_samples<TypeParam::value>(
          model, mbk::to_string(type) + " order " + std::to_string(order));
    }
}

// Mixed trees; a chain deep enough for the Newton-Schulz step (every 32 joints); the human model;
// pr2 (mimic joints, set in each lane from their sources); a mixed tree on the generic kernel
// alone, which the lanes refuse.
TYPED_TEST(SamplesInLanes, ModelsLaneByLane) {
  for (unsigned seed = 1; seed <= 3; ++seed)
    expect_lanes_are_samples<TypeParam::value>(mbk_test::random_tree(40, seed),
                                               "mixed " + std::to_string(seed));
  expect_lanes_are_samples<TypeParam::value>(mbk_test::revolute_chain(70), "chain of 70");
  expect_lanes_are_samples<TypeParam::value>(
      mbk::load_model_file(mbk_test::source_path("config/human_body.urdf")), "human");
  const mbk::Model pr2 = mbk::load_model_file(mbk_test::source_path("test/robots/pr2.urdf"));
  ASSERT_FALSE(pr2.mimics.empty());
  expect_lanes_are_samples<TypeParam::value>(pr2, "pr2");
  mbk::Model generic = mbk_test::random_tree(12, 4);
  generic.steps = mbk::make_body_steps(generic, mbk::KernelChoice::kGenericOnly);
  ASSERT_TRUE(has_generic_kernel(generic));
  expect_lanes_are_samples<TypeParam::value>(generic, "generic kernels");
}

}  // namespace
