// bvh_player's schedule and messages (mb_kinematics/ros/frame_player.h), no ROS master: frames
// in order at frame_time / rate, the pause at each loop, the end without a loop, and the
// parameters it refuses.
#include "mb_kinematics/ros/frame_player.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace {

// Three frames of two coordinates: frame f holds (10 f, 10 f + 1).
mbk_ros::PlayerFrames three_frames() {
  mbk_ros::PlayerFrames f;
  f.names = {"Hips/x", "LeftKnee/alpha"};
  f.positions = {0, 1, 10, 11, 20, 21};
  f.frame_count = 3;
  f.frame_time = 0.01;
  return f;
}

TEST(FramePlayer, FramesInOrderThenThePauseThenAgain) {
  mbk_ros::PlayerOptions options;
  options.rate = 2;           // period 0.005 s
  options.loop_pause = 0.01;  // two ticks
  const mbk_ros::FramePlayer player(three_frames(), options);
  EXPECT_DOUBLE_EQ(player.period(), 0.005);
  const long expected[] = {0, 1, 2, -1, -1, 0, 1, 2, -1, -1, 0};
  for (long tick = 0; tick < 11; ++tick) EXPECT_EQ(player.frame_at(tick), expected[tick]) << tick;
}

TEST(FramePlayer, WithoutLoopItEndsAfterTheLastFrame) {
  mbk_ros::PlayerOptions options;
  options.loop = false;
  const mbk_ros::FramePlayer player(three_frames(), options);
  EXPECT_DOUBLE_EQ(player.period(), 0.01);
  EXPECT_EQ(player.frame_at(2), 2);
  EXPECT_EQ(player.frame_at(3), -2);
}

TEST(FramePlayer, FillsNamesAndTheFramesPositions) {
  const mbk_ros::FramePlayer player(three_frames(), mbk_ros::PlayerOptions());
  sensor_msgs::JointState msg;
  msg.velocity = {5};
  player.fill(2, msg);
  EXPECT_EQ(msg.name, (std::vector<std::string>{"Hips/x", "LeftKnee/alpha"}));
  EXPECT_EQ(msg.position, (std::vector<double>{20, 21}));
  EXPECT_TRUE(msg.velocity.empty());
}

// The message of the std::invalid_argument check_player throws ("" if none).
std::string refusal(const mbk_ros::PlayerFrames& frames, const mbk_ros::PlayerOptions& options) {
  try {
    mbk_ros::check_player(frames, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(FramePlayer, RefusesWhatCannotPlay) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  mbk_ros::PlayerOptions options;
  EXPECT_EQ(refusal(three_frames(), options), "");
  for (double rate : {0.0, -1.0, nan}) {
    options.rate = rate;
    EXPECT_NE(refusal(three_frames(), options).find("~rate"), std::string::npos) << rate;
  }
  options = mbk_ros::PlayerOptions();
  options.loop_pause = -1;
  EXPECT_NE(refusal(three_frames(), options).find("~loop_pause"), std::string::npos);
  options = mbk_ros::PlayerOptions();
  mbk_ros::PlayerFrames frames = three_frames();
  frames.frame_count = 0;
  EXPECT_NE(refusal(frames, options).find("no frames"), std::string::npos);
  frames = three_frames();
  frames.frame_time = 0;
  EXPECT_NE(refusal(frames, options).find("frame time"), std::string::npos);
}

// A period frame_time / rate no ROS stamp or duration holds (a ros::Duration of more than 2^31
// s threw out of bvh_player's loop, exit 134): refused, naming ~rate.
TEST(FramePlayer, RefusesAPeriodNoStampHolds) {
  mbk_ros::PlayerOptions options;
  mbk_ros::PlayerFrames frames = three_frames();
  for (double rate : {1e-12, 1e12}) {
    options.rate = rate;
    const std::string message = refusal(frames, options);
    EXPECT_NE(message.find("~rate"), std::string::npos) << rate << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  options = mbk_ros::PlayerOptions();
  frames.frame_time = 1e300;
  EXPECT_NE(refusal(frames, options).find("longest ROS duration"), std::string::npos);
  frames = three_frames();
  options.loop_pause = 1e300;
  EXPECT_NE(refusal(frames, options).find("~loop_pause"), std::string::npos);
}

// Stamps on the ideal schedule to the nanosecond, and none past what a ros::Time holds.
TEST(FramePlayer, StampsUntilTheLastRosTime) {
  mbk_ros::PlayerOptions options;
  options.rate = 1e-9;  // a frame every 1e7 s
  const mbk_ros::FramePlayer player(three_frames(), options);
  const ros::Time start(1.8e9);
  EXPECT_EQ(player.stamp_at(start, 0), start);
  EXPECT_EQ(player.stamp_at(start, 249), ros::Time(1.8e9 + 249e7));
  EXPECT_FALSE(player.stamp_at(start, 250).has_value());  // 4.3e9 s: past 2^32 - 1
  const mbk_ros::FramePlayer fast(three_frames(), mbk_ros::PlayerOptions());
  EXPECT_EQ(fast.stamp_at(ros::Time(100, 5), 3), ros::Time(100, 30000005));
}

}  // namespace
