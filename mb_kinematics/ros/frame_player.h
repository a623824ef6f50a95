// Plays recorded frames of joint positions (a BVH file's, as bvh_player does) as
// sensor_msgs/JointState: one message per frame, stamped on the ideal schedule start + i *
// frame_time / rate (no timer jitter in the stamps the node differentiates), looping with a
// pause between the last frame and the first.
#pragma once

#include <ros/time.h>
#include <sensor_msgs/JointState.h>

#include <optional>
#include <string>
#include <vector>

namespace mbk_ros {

struct PlayerFrames {
  std::vector<std::string> names;  // the coordinates, in the order of each frame's values
  std::vector<double> positions;   // frame-major: frame_count x names.size()
  int frame_count = 0;
  double frame_time = 0;  // seconds between frames in the recording
};

struct PlayerOptions {
  double rate = 1.0;        // ~rate: playback speed (2: twice as fast)
  bool loop = true;         // ~loop: start again after the last frame
  double loop_pause = 1.5;  // ~loop_pause (s): no message between the last frame and the first
};

// The frames of the BVH file at `path` as the coordinates of its model (io/bvh_model.h, names
// and order of model_from_bvh): radians, positions times `scale` metres; rotations unwrapped
// at +-180 degrees so that the node differentiates no jump. Throws std::invalid_argument
// "<path>:<line>: ..." for a file the loader refuses.
PlayerFrames bvh_player_frames(const std::string& path, double scale);

// Throws std::invalid_argument naming the parameter if `options` cannot play `frames` (rate
// not positive and finite, a negative pause or one longer than a ROS duration holds, no frames,
// a frame time not positive, a period frame_time / rate shorter than a nanosecond or longer
// than a ROS duration holds).
void check_player(const PlayerFrames& frames, const PlayerOptions& options);

// The schedule: tick i (i = 0, 1, ...) is at start + i * period(); each tick either publishes
// a frame or is part of the pause at a loop.
class FramePlayer {
 public:
  FramePlayer(PlayerFrames frames, const PlayerOptions& options);  // check_player first
  double period() const { return period_; }  // wall seconds per frame: frame_time / rate
  // The stamp of tick `tick`, start + tick * period(); nullopt once the schedule has passed
  // what a ros::Time holds (the year 2106).
  std::optional<ros::Time> stamp_at(const ros::Time& start, long tick) const;
  // The frame tick `tick` publishes, or -1 during a loop's pause; -2 when the playback is over
  // (no loop, past the last frame).
  long frame_at(long tick) const;
  // `msg` holds frame `frame`'s names and positions (no velocities); the stamp is the caller's.
  void fill(long frame, sensor_msgs::JointState& msg) const;

 private:
  PlayerFrames frames_;
  double period_;
  long pause_ticks_;  // ticks of silence at each loop
  bool loop_;
};

}  // namespace mbk_ros
