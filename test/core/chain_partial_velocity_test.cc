// Partial velocities of chosen bodies along their chains only (chain_partial_velocity.h):
// the same columns as the whole tree's arrays (independent_columns of
// partial_velocity_kinematics) on random trees, with mimics and with angular velocity speeds;
// and on a 10,000-link chain a request for the tip takes chain-sized memory and little time
// (the whole tree's arrays would be 50 million columns, 7.2 GB).
#include "mb_kinematics/core/chain_partial_velocity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "test/support/allocation_counter.h"

namespace {

using V = mbk::Vec3<double>;
constexpr double kRelative = 1e-13;

// |got - want| <= kRelative * scale for each quantity, scale: the largest column of that
// quantity of the body (a column small by cancellation is compared at its body's scale).
void expect_same_columns(const mbk::Model& model, const std::vector<mbk::SpeedColumn>& got,
                         const std::vector<mbk::SpeedColumn>& want, int k) {
  const std::string where = "body " + model.bodies[k].name;
  ASSERT_EQ(got.size(), want.size()) << where;
  V mbk::SpeedColumn::*fields[] = {&mbk::SpeedColumn::omega, &mbk::SpeedColumn::velocity,
                                   &mbk::SpeedColumn::omega_dot, &mbk::SpeedColumn::velocity_dot};
  for (auto field : fields) {
    double scale = 1e-300;
    for (const mbk::SpeedColumn& c : want) scale = std::max(scale, (c.*field).norm());
    for (size_t i = 0; i < want.size(); ++i) {
      ASSERT_EQ(got[i].speed, want[i].speed) << where << " column " << i;
      EXPECT_LE((got[i].*field - want[i].*field).norm(), kRelative * scale)
          << where << ", speed " << model.speed_names[want[i].speed];
    }
  }
}

// Every body alone, and a random set of bodies (repeats included) in one request.
void expect_whole_tree_columns(const mbk::Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  const mbk::JointState<double> state = mbk::random_state(model, rng);
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> data(model);
  mbk::partial_velocity_kinematics(model, state, pv, data);
  for (int k = 1; k <= model.body_count(); ++k)
    expect_same_columns(model, mbk::chain_partial_velocities(model, state, {k})[0],
                        mbk::independent_columns(model, pv, k), k);
  std::vector<int> some;
  for (int i = 0; i < 7; ++i) some.push_back(1 + static_cast<int>(rng() % model.body_count()));
  const auto got = mbk::chain_partial_velocities(model, state, some);
  ASSERT_EQ(got.size(), some.size());
  for (size_t i = 0; i < some.size(); ++i)
    expect_same_columns(model, got[i], mbk::independent_columns(model, pv, some[i]), some[i]);
}

TEST(ChainPartialVelocities, SameAsTheWholeTreeOnRandomTrees) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_whole_tree_columns(mbk::make_random_tree(60, seed), seed);
    expect_whole_tree_columns(mbk::make_random_tree(40, seed, mbk::SpeedKind::kAngularVelocity),
                              seed);
  }
}

// Deep chains: the chain's sums of O_k - O_b against the whole tree's running sums.
TEST(ChainPartialVelocities, SameAsTheWholeTreeOnDeepChains) {
  expect_whole_tree_columns(mbk::make_chain(600, mbk::JointType::kRevolute), 7);
  expect_whole_tree_columns(mbk::make_chain(300, mbk::JointType::kBall123), 8);
  expect_whole_tree_columns(mbk::make_random_tree(500, 9), 9);
}

// Mimic coordinates (a mimic of a mimic too): their columns fold into their sources'.
TEST(ChainPartialVelocities, MimicColumnsFoldAsTheWholeTree) {
  mbk::Model model = mbk::make_random_revolute_tree(30, 3);
  model.mimics = {{5, 2, -2.0, 0.1}, {9, 5, 1.5, 0.0}, {20, 11, 0.5, -0.3}};
  mbk::finalize_model(model);
  expect_whole_tree_columns(model, 4);
}

// The tip of a 10,000-link chain: its 10,000 columns, in chain-sized memory and little time.
TEST(ChainPartialVelocities, TipOfADeepChainCostsItsChainOnly) {
  constexpr int kLinks = 10000;
  const mbk::Model model = mbk::make_chain(kLinks, mbk::JointType::kRevolute);
  std::mt19937 rng(5);
  const mbk::JointState<double> state = mbk::random_state(model, rng);
  const long before = mbk_test::allocation_counts().new_bytes;
  const auto start = std::chrono::steady_clock::now();
  const auto got = mbk::chain_partial_velocities(model, state, {kLinks});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long bytes = mbk_test::allocation_counts().new_bytes - before;
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(static_cast<long>(got[0].size()), mbk::chain_speed_counts(model)[kLinks]);
  EXPECT_EQ(got[0].size(), static_cast<size_t>(kLinks));
  // Chain-sized: about 500 bytes per link here; the whole tree's arrays take 144 bytes per
  // column, 7.2 GB for the 50 million columns of this chain.
  EXPECT_LT(bytes, 1000L * kLinks) << bytes << " bytes";
  EXPECT_LT(seconds, 0.25) << seconds << " s";
  for (const mbk::SpeedColumn& c : got[0])
    ASSERT_TRUE(c.omega.allFinite() && c.velocity.allFinite() && c.velocity_dot.allFinite());
}

TEST(ChainPartialVelocities, ChainSpeedCountsAreTheStoredColumns) {
  const mbk::Model model = mbk::make_random_tree(50, 9);
  const mbk::PartialVelocities<double> pv(model);
  const std::vector<long> counts = mbk::chain_speed_counts(model);
  ASSERT_EQ(counts.size(), model.bodies.size());
  EXPECT_EQ(counts[0], 0);
  for (int k = 1; k <= model.body_count(); ++k) EXPECT_EQ(counts[k], pv.count[k]) << k;
}

}  // namespace
