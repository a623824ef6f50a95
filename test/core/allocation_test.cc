// No heap allocation per update (doc/method.md 8): once Model, JointState, Data and
// PartialVelocities exist, forward_kinematics and partial_velocity_kinematics allocate nothing,
// at every level. Global operator new / new[] are replaced by counting versions; on glibc,
// malloc is counted too, since Eigen's dynamic vectors allocate with malloc, not new
// (test/support/allocation_counter.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "test/support/allocation_counter.h"
#include "test/support/test_models.h"

namespace {

const std::vector<int> kHuman = {0, 1, 2, 3, 4, 5, 4, 7, 4, 9, 2, 11, 12, 2, 14, 15};
const mbk::Level kLevels[] = {mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration};

using Counts = mbk_test::AllocationCounts;
Counts counts() { return mbk_test::allocation_counts(); }

// Runs every update of both formulations (several times, at every level) between two counts.
void expect_no_allocation(const mbk::Model& model, const mbk::JointState<double>& state,
                          const std::string& tag) {
  mbk::Data<double> data(model);
  mbk::PartialVelocities<double> pv(model);
  const Counts before = counts();
  for (int repeat = 0; repeat < 3; ++repeat)
    for (mbk::Level level : kLevels) {
      mbk::forward_kinematics(model, state, data, level);
      mbk::partial_velocity_kinematics(model, state, pv, data, level);
    }
  const Counts after = counts();
  EXPECT_EQ(after.news, before.news) << tag << ": operator new during an update";
  EXPECT_EQ(after.mallocs, before.mallocs) << tag << ": malloc during an update";
}

// The counters see what the test is looking for, so the tests below can fail.
TEST(Allocation, CountersSeeNewAndEigenAllocations) {
  const Counts before = counts();
  int* volatile p = new int(1);
  delete p;
  EXPECT_EQ(counts().news, before.news + 1);
#if MBK_COUNT_MALLOC
  const Counts middle = counts();
  Eigen::VectorXd v(100);  // Eigen's dynamic storage: malloc, not operator new
  asm volatile("" : : "g"(v.data()) : "memory");  // keep the allocation
  EXPECT_GT(counts().mallocs, middle.mallocs);
#endif
}

TEST(Allocation, NoneInUpdatesOnRandomTrees) {
  for (mbk::SpeedKind kind :
       {mbk::SpeedKind::kCoordinateDerivatives, mbk::SpeedKind::kAngularVelocity})
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const mbk::Model model = mbk_test::random_tree(40, seed, kind);
      const mbk::Model coords = mbk_test::random_tree(40, seed);
      const mbk_test::Trajectory trajectory(coords, seed);
      const mbk::JointState<double> state =
          kind == mbk::SpeedKind::kAngularVelocity
              ? mbk_test::state_with_angular_speeds(model, coords, trajectory, 0.5)
              : trajectory.at<double>(0.5);
      expect_no_allocation(model, state, "random tree seed " + std::to_string(seed));
    }
}

TEST(Allocation, NoneInUpdatesOnTheHumanBodyModel) {
  for (mbk::JointType type :
       {mbk::JointType::kRevolute, mbk::JointType::kBall123, mbk::JointType::kFreeEuler}) {
    const mbk::Model model = mbk::make_bare_model(kHuman, type);
    const mbk::JointState<double> state = mbk_test::Trajectory(model, 7).at<double>(1.0);
    expect_no_allocation(model, state, "human body model, " + mbk::to_string(type));
  }
}

}  // namespace
