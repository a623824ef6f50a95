// Which bodies the known coordinates place (core/known_bodies.h): a body needs its own joint's
// coordinates and those of its whole chain to R; a mimic needs its source's.
#include "mb_kinematics/core/known_bodies.h"

#include <gtest/gtest.h>

#include "mb_kinematics/io/urdf_model.h"

namespace {

// Fig. 4.2.1's ten-body system: L = (0 1 2 1 1 5 2 7 8 9), ball joints (3 coordinates each).
const std::vector<int> kTenBody = {0, 1, 2, 1, 1, 5, 2, 7, 8, 9};

std::vector<char> known_coordinates(const mbk::Model& model,
                                    const std::vector<int>& unknown_bodies) {
  std::vector<char> known(model.nq, 1);
  for (int k : unknown_bodies) known[model.bodies[k].q_index + 1] = 0;  // one of its three angles
  return known;
}

TEST(KnownBodies, EverythingKnownPlacesEveryBody) {
  const mbk::Model model = mbk::make_bare_model(kTenBody, mbk::JointType::kBall123);
  std::vector<char> coordinates(model.nq, 1), bodies;
  EXPECT_EQ(mbk::known_bodies(model, coordinates, bodies), 10);
  EXPECT_EQ(bodies, std::vector<char>(11, 1));
}

TEST(KnownBodies, AMissingCoordinateHidesItsBodyAndEveryBodyOutboard) {
  const mbk::Model model = mbk::make_bare_model(kTenBody, mbk::JointType::kBall123);
  // Body 7's joint: 7 and its outboard chain 8, 9, 10 (L(8) = 7, L(9) = 8, L(10) = 9).
  std::vector<char> coordinates = known_coordinates(model, {7}), bodies;
  EXPECT_EQ(mbk::known_bodies(model, coordinates, bodies), 6);
  const std::vector<char> expected = {1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0};
  EXPECT_EQ(bodies, expected);
  // Body 5's too: 5 and 6 (L(6) = 5) go as well; the rest stay.
  coordinates = known_coordinates(model, {7, 5});
  EXPECT_EQ(mbk::known_bodies(model, coordinates, bodies), 4);
  const std::vector<char> expected2 = {1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(bodies, expected2);
  // Body 1's: every body's chain passes through B1.
  coordinates = known_coordinates(model, {1});
  EXPECT_EQ(mbk::known_bodies(model, coordinates, bodies), 0);
  EXPECT_EQ(bodies, (std::vector<char>{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
}

// A fixed joint has no coordinate: it is known iff its lower body is. A mimic coordinate is
// known iff its source is, whatever the caller said of the mimic itself.
TEST(KnownBodies, FixedJointsFollowTheirLowerBodyAndMimicsTheirSource) {
  const mbk::Model model = mbk::load_urdf_string(R"(<robot name="r">
    <link name="base"/><link name="arm"/><link name="hand"/><link name="finger"/>
    <link name="wheel"/>
    <joint name="arm_joint" type="continuous"><parent link="base"/><child link="arm"/>
      <axis xyz="0 0 1"/></joint>
    <joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/>
      <axis xyz="0 1 0"/></joint>
    <joint name="hand_joint" type="fixed"><parent link="arm"/><child link="hand"/></joint>
    <joint name="finger_joint" type="continuous"><parent link="hand"/><child link="finger"/>
      <axis xyz="1 0 0"/><mimic joint="wheel_joint" multiplier="2"/></joint>
  </robot>)");
  ASSERT_EQ(model.body_count(), 4);
  const int arm = model.body_index("arm"), wheel = model.body_index("wheel"),
            hand = model.body_index("hand"), finger = model.body_index("finger");
  const int arm_q = model.coordinate_index("arm_joint"),
            wheel_q = model.coordinate_index("wheel_joint"),
            finger_q = model.coordinate_index("finger_joint");
  std::vector<char> coordinates(model.nq, 1), bodies;
  coordinates[wheel_q] = 0;  // the mimic's source never came; the mimic's own flag says 1
  EXPECT_EQ(mbk::known_bodies(model, coordinates, bodies), 2);
  EXPECT_TRUE(bodies[arm] && bodies[hand]);
  EXPECT_FALSE(bodies[wheel]);
  EXPECT_FALSE(bodies[finger]) << "a mimic of an unknown coordinate";
  EXPECT_EQ(coordinates[finger_q], 0) << "mimic flag not taken from its source";
  std::fill(coordinates.begin(), coordinates.end(), 1);
  coordinates[arm_q] = 0;
  coordinates[finger_q] = 0;  // ignored: its source is known
  EXPECT_EQ(mbk::known_bodies(model, coordinates, bodies), 1);
  EXPECT_TRUE(bodies[wheel]);
  EXPECT_FALSE(bodies[arm] || bodies[hand] || bodies[finger]) << "outboard of arm_joint";
}

TEST(KnownBodies, WrongSizeIsRefused) {
  const mbk::Model model = mbk::make_bare_model(kTenBody, mbk::JointType::kBall123);
  std::vector<char> coordinates(model.nq - 1, 1), bodies;
  EXPECT_THROW(mbk::known_bodies(model, coordinates, bodies), std::invalid_argument);
}

}  // namespace
