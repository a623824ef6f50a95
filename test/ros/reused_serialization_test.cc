// /tf's and body_kinematics' bytes (outputs/reused_serialization.h): a sample that changes only
// the numbers is written into the last sample's bytes, and those bytes are, bit for bit, what
// ros::serialization::serializeMessage makes of the message; so are they after reshape(), after
// a length changed without it, and while the last bytes are still held by a subscriber's queue.
// No ROS master: serialize() is what publish hands roscpp for remote subscribers.
#include "mb_kinematics/ros/outputs/reused_serialization.h"

#include <gtest/gtest.h>
#include <ros/serialization.h>

#include <cstring>
#include <string>
#include <vector>

#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/messages/body_kinematics.h"
#include "mb_kinematics/messages/tf.h"
#include "test/support/test_models.h"

namespace {

using mb_kinematics_msgs::BodyKinematicsArray;
using mbk_ros::ReusedSerialization;
using tf2_msgs::TFMessage;

// `bytes` are serializeMessage's of `msg`, length prefix and message start included.
template <typename M>
void expect_serialized(const ros::SerializedMessage& bytes, const M& msg, const std::string& what) {
  const ros::SerializedMessage want = ros::serialization::serializeMessage(msg);
  ASSERT_EQ(bytes.num_bytes, want.num_bytes) << what;
  EXPECT_EQ(bytes.message_start, bytes.buf.get() + 4) << what;
  EXPECT_EQ(std::memcmp(bytes.buf.get(), want.buf.get(), want.num_bytes), 0) << what;
}

std::vector<int> every_other(const std::vector<int>& bodies) {
  std::vector<int> out;
  for (size_t i = 0; i < bodies.size(); i += 2) out.push_back(bodies[i]);
  return out;
}

TEST(ReusedSerialization, TfBytesAreSerializeMessages) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = mbk_test::random_tree(60, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    const mbk_messages::FrameNames names(model, "p" + std::to_string(seed) + "/", "world");
    const std::vector<int> all = mbk_messages::moving_bodies(model);
    std::vector<mbk_messages::TfJoint> moving;
    ReusedSerialization<TFMessage> tf;
    mbk_messages::init_transforms(model, names, all, moving, tf.reshape().transforms);
    const uint8_t* image = nullptr;
    for (int sample = 0; sample < 6; ++sample) {
      const std::string what =
          "seed " + std::to_string(seed) + ", sample " + std::to_string(sample);
      if (sample == 3)  // fewer bodies, other frames: serialized whole
        mbk_messages::init_transforms(model, names, every_other(all), moving,
                                      tf.reshape().transforms);
      TFMessage& msg = tf.next();
      mbk_messages::fill_transforms(model, trajectory.at<double>(0.1 * sample), moving,
                                    ros::Time(1.0 + sample, 7 * sample), msg.transforms);
      const ros::SerializedMessage bytes = tf.serialize();
      expect_serialized(bytes, msg, what);
      if (sample != 0 && sample != 3) {  // numbers only: into the last sample's bytes
        EXPECT_EQ(bytes.buf.get(), image) << what;
      }
      image = bytes.buf.get();
    }
  }
}

TEST(ReusedSerialization, BodyKinematicsBytesAreSerializeMessages) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const mbk::Model model = mbk_test::random_tree(60, seed);
    const mbk_test::Trajectory trajectory(model, seed);
    mbk::Data<double> data(model);
    ReusedSerialization<BodyKinematicsArray> out;
    mbk_messages::init_body_kinematics(model, "world", out.reshape(), {"left hand", "right hand"});
    std::vector<char> published(model.body_count() + 1, 1);
    const uint8_t* image = nullptr;
    for (int sample = 0; sample < 6; ++sample) {
      const std::string what =
          "seed " + std::to_string(seed) + ", sample " + std::to_string(sample);
      if (sample == 3) {  // ~missing_coordinates skip: every other body left out
        for (int k = 1; k <= model.body_count(); k += 2) published[k] = 0;
        mbk_messages::select_body_kinematics(model, published, out.reshape());
      }
      mbk::forward_kinematics(model, trajectory.at<double>(0.1 * sample), data,
                              mbk::Level::kAcceleration);
      BodyKinematicsArray& msg = out.next();
      mbk_messages::fill_kinematics(ros::Time(1.0 + sample, 3 * sample), model, data, sample < 3,
                                    msg);
      const ros::SerializedMessage bytes = out.serialize();
      expect_serialized(bytes, msg, what);
      if (sample != 0 && sample != 3) {
        EXPECT_EQ(bytes.buf.get(), image) << what;
      }
      image = bytes.buf.get();
    }
  }
}

// Bytes still held (queued for a subscriber) are left as they were: the next sample's numbers
// go into a copy.
TEST(ReusedSerialization, HeldBytesAreNotWrittenOver) {
  const mbk::Model model = mbk_test::random_tree(30, 4);
  const mbk_test::Trajectory trajectory(model, 4);
  mbk::Data<double> data(model);
  ReusedSerialization<BodyKinematicsArray> out;
  mbk_messages::init_body_kinematics(model, "world", out.reshape());
  mbk::forward_kinematics(model, trajectory.at<double>(0.1), data, mbk::Level::kAcceleration);
  mbk_messages::fill_kinematics(ros::Time(1.0), model, data, true, out.next());
  const BodyKinematicsArray first = out.next();
  const ros::SerializedMessage held = out.serialize();
  mbk::forward_kinematics(model, trajectory.at<double>(0.2), data, mbk::Level::kAcceleration);
  mbk_messages::fill_kinematics(ros::Time(2.0), model, data, true, out.next());
  const ros::SerializedMessage second = out.serialize();
  EXPECT_NE(second.buf.get(), held.buf.get());
  expect_serialized(held, first, "the held bytes");
  expect_serialized(second, out.next(), "the next sample's");
}

// A string or array whose length changed without reshape() (against the class's contract) is
// found by its length in the bytes, and the message serialized whole.
TEST(ReusedSerialization, LengthChangedWithoutReshapeIsSerializedWhole) {
  const mbk::Model model = mbk_test::random_tree(20, 5);
  const mbk_messages::FrameNames names(model, "", "world");
  std::vector<mbk_messages::TfJoint> moving;
  ReusedSerialization<TFMessage> tf;
  mbk_messages::init_transforms(model, names, mbk_messages::moving_bodies(model), moving,
                                tf.reshape().transforms);
  tf.serialize();
  tf.next().transforms.back().child_frame_id += "_longer";
  expect_serialized(tf.serialize(), tf.next(), "a longer frame");
  tf.next().transforms.pop_back();
  expect_serialized(tf.serialize(), tf.next(), "a transform fewer");
  tf.next().transforms.clear();
  expect_serialized(tf.serialize(), tf.next(), "no transform");
}

}  // namespace
