// The one joint-state intake (core/joint_state_intake.h) of the node and of recordings: each
// problem named in the sample's order, names looked up again only when they change, and Euler
// parameters kept on one side of e / -e with their velocities.
#include "mb_kinematics/core/joint_state_intake.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

mbk::Model two_joints() {  // coordinates "J1" and "J2"
  return mbk::make_bare_model({0, 1}, mbk::JointType::kRevolute);
}

TEST(JointStateIntakeTest, TheFirstProblemInTheSamplesOrder) {
  const mbk::Model model = two_joints();
  mbk::JointStateIntake intake(model);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  using P = mbk::SampleProblem;
  const struct {
    std::vector<std::string> names;
    std::vector<double> position, velocity;
    const char* error;
    P problem;
  } cases[] = {
      {{"J1", "J2"}, {0.1}, {}, "2 names but 1 positions", P::kUnequalLengths},
      {{"J1", "J2"}, {0.1, 0.2}, {1}, "2 names but 1 velocities", P::kUnequalLengths},
      {{"J1", "J1"}, {0.1, 0.2}, {}, "joint 'J1' is named twice", P::kDuplicateName},
      {{"J2", "J1"}, {nan, 0.2}, {}, "joint 'J2': position is NaN", P::kNonFinite},
      {{"J1", "J2"}, {0.1, 0.2}, {0, -inf}, "joint 'J2': velocity is Inf", P::kNonFinite},
      // An unknown name is no problem, even twice or not finite; the first problem counts.
      {{"x", "x", "J1"}, {nan, 1, inf}, {}, "joint 'J1': position is Inf", P::kNonFinite},
      {{"J1", "J1", "J2"}, {nan, 0, 0}, {}, "joint 'J1': position is NaN", P::kNonFinite},
      {{"J1", "J2", "J2"}, {nan, 0, 0}, {}, "joint 'J1': position is NaN", P::kNonFinite},
      {{"J1", "J2", "J1"}, {0, 0, nan}, {}, "joint 'J1' is named twice", P::kDuplicateName},
      {{"J2", "y", "J1"}, {0.1, nan, 0.2}, {}, "", P::kNone},
  };
  for (const auto& c : cases) {
    EXPECT_EQ(intake.check(c.names, c.position, c.velocity), c.error) << c.error;
    EXPECT_EQ(intake.problem(), c.problem) << c.error;
  }
  EXPECT_EQ(intake.coordinates(), (std::vector<int>{1, -1, 0}));
  EXPECT_EQ(intake.unknown(), std::vector<std::string>{"y"});
  EXPECT_EQ(intake.take({0.1, 0.0, 0.2}), 0);
  EXPECT_EQ(intake.last(), (std::vector<double>{0.2, 0.1}));
  EXPECT_TRUE(intake.taken(0) && intake.taken(1));
}

// A sample that names a joint's four Euler parameters with a negative dot product against the
// last ones is negated (sign -1 on those four, for positions and velocities alike); a sample
// naming only some of them, or the first, is taken as given.
TEST(JointStateIntakeTest, EulerParametersStayOnOneSide) {
  const mbk::Model model = mbk::make_bare_model({0}, mbk::JointType::kBallEuler);
  const std::vector<std::string>& n = model.coordinate_names;  // J1/e1 .. J1/e4
  mbk::JointStateIntake intake(model);
  ASSERT_EQ(intake.check(n, {0.1, 0, 0, -0.99}, {}), "");
  EXPECT_EQ(intake.take({0.1, 0, 0, -0.99}), 0);  // the first: nothing to compare with
  ASSERT_EQ(intake.check(n, {-0.1, 0, 0, 0.99}, {}), "");
  EXPECT_EQ(intake.take({-0.1, 0, 0, 0.99}), 1);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(intake.sign(i), -1.0);
  EXPECT_EQ(intake.last(), (std::vector<double>{0.1, 0, 0, -0.99}));
  const std::vector<std::string> three(n.begin(), n.begin() + 3);
  ASSERT_EQ(intake.check(three, {-0.1, 0, 0}, {}), "");
  EXPECT_EQ(intake.take({-0.1, 0, 0}), 0);  // not whole: as given
  EXPECT_EQ(intake.sign(0), 1.0);
  EXPECT_EQ(intake.last(), (std::vector<double>{-0.1, 0, 0, -0.99}));
}

// CoordinateLookup compares a sample's names with the last ones word by word (joint_state_intake.cc
// same_bytes): every length from 0 to 40 and a name differing from the last in any one byte (the
// words of each length, their overlapping tails) or in its length is told apart; the same names,
// in strings of their own, are not.
TEST(JointStateIntakeTest, NamesComparedWordByWord) {
  const mbk::Model model = two_joints();
  mbk::CoordinateLookup lookup(model);
  for (size_t n = 0; n <= 40; ++n) {
    std::string name;
    for (size_t i = 0; i < n; ++i) name += static_cast<char>('a' + i % 26);
    const std::vector<std::string> names{"J1", name, "J2"};
    bool changed = false;
    lookup.look_up(names, &changed);
    lookup.look_up(std::vector<std::string>(names), &changed);  // equal, not the same storage
    EXPECT_FALSE(changed) << n;
    for (size_t i = 0; i < n; ++i) {
      std::vector<std::string> other = names;
      other[1][i] ^= 0x20;
      lookup.look_up(other, &changed);
      EXPECT_TRUE(changed) << n << " " << i;
      lookup.look_up(names, &changed);
      EXPECT_TRUE(changed) << n << " " << i;
    }
    for (const std::string& other : {name + "a", name.substr(0, n ? n - 1 : 0)}) {
      if (other == name) continue;
      lookup.look_up({"J1", other, "J2"}, &changed);
      EXPECT_TRUE(changed) << n;
      lookup.look_up(names, &changed);
      EXPECT_TRUE(changed) << n;
    }
  }
  bool changed = false;
  lookup.look_up({"J1", "J2"}, &changed);
  EXPECT_TRUE(changed);  // fewer names
  EXPECT_EQ(lookup.coordinates(), (std::vector<int>{0, 1}));
}

}  // namespace
