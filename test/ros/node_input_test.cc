// NodeInput's models (mb_kinematics/ros/node_input.h), no master needed: without
// ~base_odometry the input and the kinematics read the loaded model itself (no copies: 8 MB saved
// at 10,000 bodies), also after a reload to another model; with it, the model split in two.
#include "mb_kinematics/ros/node_input.h"

#include <gtest/gtest.h>

#include "test/support/test_models.h"

namespace {

TEST(NodeInput, WithoutBaseOdometryEveryModelIsTheLoadedOne) {
  const mbk_ros::NodeParams params;
  mbk_ros::NodeInput input(params, "");
  for (const int n : {12, 30}) {  // at start, then ~reload to another model
    input.load(mbk_test::random_tree(n, 1));
    EXPECT_EQ(&input.model(), &input.loaded());
    EXPECT_EQ(input.model().body_count(), n);
    EXPECT_EQ(input.state().position.size(), input.model().nq);
  }
}

TEST(NodeInput, WithBaseOdometryTheKinematicsModelHasTheBase) {
  mbk_ros::NodeParams params;
  params.base_odometry = "odom";
  mbk_ros::NodeInput input(params, "/odom");
  for (const int n : {12, 30}) {  // chains of revolute joints: no floating root of their own
    input.load(mbk_test::revolute_chain(n));
    EXPECT_NE(&input.model(), &input.loaded());
    EXPECT_EQ(input.loaded().body_count(), n);
    EXPECT_EQ(input.model().body_count(), n + 1);  // the base on its free joint first
    EXPECT_EQ(input.state().position.size(), input.model().nq);
  }
}

}  // namespace
