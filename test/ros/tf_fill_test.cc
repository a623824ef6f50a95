// messages/tf.h's fill_transforms: every moving body's rotation is mbk::joint_quaternion's (the
// quaternion test/core/joint_traits_test.cc checks against joint_motion), equal to the last bit (a
// zero's sign aside), whether its sine and cosine are taken with the other plain turns' (revolute
// joints without an offset rotation, more than one block of them) or alone; every translation
// q_k + s_k. No ROS master needed.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/messages/frames.h"
#include "mb_kinematics/messages/tf.h"
#include "test/support/test_models.h"

namespace {

// Bit for bit, but for the sign of a zero (joint_quaternion's product with the identity C_k
// gives +0 or -0 by component).
void expect_bits(double got, double want) {
  if (got == 0 && want == 0) return;
  EXPECT_EQ(std::memcmp(&got, &want, sizeof got), 0) << got << " against " << want;
}

// The transforms of every moving body of `model` at `state`, frames left empty.
std::vector<geometry_msgs::TransformStamped> filled(
    const mbk::Model& model, const std::vector<mbk_messages::TfJoint>& moving,
    const mbk::JointState<double>& state) {
  std::vector<geometry_msgs::TransformStamped> transforms(moving.size());
  mbk_messages::fill_transforms(model, state, moving, ros::Time(2.0), transforms);
  return transforms;
}

// Each rotation equals joint_quaternion's; returns how many bodies were plain turns.
int expect_joint_quaternions(const mbk::Model& model, const mbk::JointState<double>& state) {
  std::vector<mbk_messages::TfJoint> moving;
  for (const int k : mbk_messages::moving_bodies(model))
    moving.push_back(mbk_messages::tf_joint(model, k));
  const std::vector<geometry_msgs::TransformStamped> transforms = filled(model, moving, state);
  int turns = 0;
  for (size_t i = 0; i < moving.size(); ++i) {
    const mbk::Body& body = model.bodies[moving[i].body];
    SCOPED_TRACE(body.name + " (" + mbk::to_string(body.joint.type) + ")");
    const Eigen::Quaterniond q =
        mbk::joint_quaternion(body.joint, moving[i].offset, state.position.data() + body.q_index);
    const geometry_msgs::Quaternion& r = transforms[i].transform.rotation;
    expect_bits(r.w, q.w());
    expect_bits(r.x, q.x());
    expect_bits(r.y, q.y());
    expect_bits(r.z, q.z());
    EXPECT_EQ(transforms[i].header.stamp, ros::Time(2.0));
    turns += moving[i].plain_turn;
  }
  return turns;
}

TEST(TfFill, PlainTurnsAreJointQuaternions) {
  const mbk::Model chain = mbk_test::revolute_chain(70);  // three blocks of turns
  const mbk_test::Trajectory trajectory(chain, 1);
  for (const double t : {0.0, 0.3, 1.7})
    EXPECT_EQ(expect_joint_quaternions(chain, trajectory.at<double>(t)), 70);
}

TEST(TfFill, EveryJointTypeIsJointQuaternion) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const mbk::Model model = mbk_test::random_tree(100, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    expect_joint_quaternions(model, trajectory.at<double>(0.4));
  }
}

// Angles past the reduction's bound and not finite take std::sin and std::cos, as
// joint_quaternion does.
TEST(TfFill, LargeAnglesAsJointQuaternion) {
  const mbk::Model chain = mbk_test::revolute_chain(5);
  mbk::JointState<double> state(chain);
  state.position << -0.5, 1e7, -3e9, 2e300, -0.0;
  EXPECT_EQ(expect_joint_quaternions(chain, state), 5);
}

// init_transforms then fill_transforms, twice (a message reused): each translation is q_k + s_k
// of joint_motion, q_k alone (set by init_transforms) on the joints that do not translate.
TEST(TfFill, TranslationsAreOffsetsPlusJointTranslations) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const mbk::Model model = mbk_test::random_tree(100, seed);
    const std::vector<int> bodies = mbk_messages::moving_bodies(model);
    std::vector<mbk_messages::TfJoint> moving;
    std::vector<geometry_msgs::TransformStamped> transforms;
    mbk_messages::init_transforms(model, mbk_messages::FrameNames(model, "", "world"), bodies,
                                  moving, transforms);
    const mbk_test::Trajectory trajectory(model, seed);
    for (const double t : {0.4, 1.1}) {
      const mbk::JointState<double> state = trajectory.at<double>(t);
      mbk_messages::fill_transforms(model, state, moving, ros::Time(t), transforms);
      for (size_t i = 0; i < bodies.size(); ++i) {
        const mbk::Body& body = model.bodies[bodies[i]];
        SCOPED_TRACE(body.name + " (" + mbk::to_string(body.joint.type) + ")");
        mbk::JointMotion<double> m;
        mbk::joint_motion<double>(body.joint, model.speeds, state.position.data() + body.q_index,
                                  nullptr, m);
        const mbk::Vec3<double> want = body.joint.offset + m.translation;
        const geometry_msgs::Vector3& got = transforms[i].transform.translation;
        expect_bits(got.x, want.x());
        expect_bits(got.y, want.y());
        expect_bits(got.z, want.z());
      }
    }
  }
}

}  // namespace
