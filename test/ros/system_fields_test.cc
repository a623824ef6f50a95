// body_kinematics' system field (doc/node.md, system, messages/system.h) as the core
// computes it, and what it says when it cannot know the angular momentum: a body with mass but
// no inertia leaves angular_momentum_known false and angular_momentum zero (nothing invented),
// and a massless model leaves the field unfilled. No ROS master: the fill function only.
#include <gtest/gtest.h>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/messages/system.h"
#include "test/support/test_models.h"

namespace {

mbk::Vec3<double> vec(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }
mbk::Vec3<double> vec(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }

mb_kinematics_msgs::SystemKinematics filled(const mbk::Model& model, unsigned seed) {
  const mbk_test::Trajectory trajectory(model, seed);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, trajectory.at<double>(0.4), data, mbk::Level::kAcceleration);
  mb_kinematics_msgs::SystemKinematics msg;
  mbk_messages::fill_system_kinematics(model, data, msg);
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model, data, s);
  // Every field is the core's value, copied (float64 to float64: exact).
  EXPECT_EQ(msg.mass, s.mass);
  EXPECT_EQ(vec(msg.mass_center), s.mass_center);
  EXPECT_EQ(vec(msg.velocity), s.velocity);
  EXPECT_EQ(vec(msg.acceleration), s.acceleration);
  EXPECT_EQ(vec(msg.linear_momentum), s.linear_momentum);
  EXPECT_EQ(vec(msg.angular_momentum), s.angular_momentum);
  return msg;
}

TEST(SystemFields, AngularMomentumKnownWhenEveryBodyWithMassHasAnInertia) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(20, seed), seed);
    ASSERT_TRUE(mbk::inertias_known(model));
    const mb_kinematics_msgs::SystemKinematics msg = filled(model, seed);
    EXPECT_TRUE(msg.filled);
    EXPECT_GT(msg.mass, 0);
    EXPECT_TRUE(msg.angular_momentum_known);
    EXPECT_GT(vec(msg.angular_momentum).norm(), 0);  // a moving tree: not zeros
  }
}

TEST(SystemFields, AngularMomentumLeftOutWithoutAnInertia) {
  mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(20, 4), 4);
  int k = 1;
  while (!(model.bodies[k].mass > 0)) ++k;
  model.bodies[k].has_inertia = false;  // one body with mass lacks its inertia
  ASSERT_EQ(mbk::bodies_without_inertia(model), std::vector<std::string>{model.bodies[k].name});
  const mb_kinematics_msgs::SystemKinematics msg = filled(model, 4);
  EXPECT_TRUE(msg.filled);  // the rest is known
  EXPECT_GT(vec(msg.velocity).norm(), 0);
  EXPECT_FALSE(msg.angular_momentum_known);
  EXPECT_EQ(vec(msg.angular_momentum), mbk::Vec3<double>::Zero());
}

TEST(SystemFields, NotFilledWithoutMass) {
  mbk::Model model = mbk_test::random_tree(10, 5);
  for (int k = 1; k <= model.body_count(); ++k) model.bodies[k].mass = 0;
  const mb_kinematics_msgs::SystemKinematics msg = filled(model, 5);
  EXPECT_FALSE(msg.filled);
  EXPECT_FALSE(msg.angular_momentum_known);
}

}  // namespace
