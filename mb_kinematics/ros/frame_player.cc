#include "mb_kinematics/ros/frame_player.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk_ros {
namespace {

constexpr double kMinPeriod = 1e-9;          // s: a stamp counts nanoseconds
constexpr double kMaxPeriod = 2147483647.0;  // s: the longest ros::Duration
constexpr double kLastStamp = 4294967295.0;  // s: the last ros::Time (2^32 - 1 s after 1970)

}  // namespace

PlayerFrames bvh_player_frames(const std::string& path, double scale) {
  mbk::BvhFile bvh = mbk::read_bvh(path);
  mbk::unwrap_rotations(bvh);
  mbk::BvhModelOptions options;
  options.scale = scale;
  const mbk::Model model = mbk::model_from_bvh(bvh, options);
  PlayerFrames frames;
  frames.names = model.coordinate_names;
  frames.frame_count = bvh.frame_count;
  frames.frame_time = bvh.frame_time;
  frames.positions.reserve(static_cast<size_t>(bvh.frame_count) * model.nq);
  for (int f = 0; f < bvh.frame_count; ++f) {
    const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, model, f, scale);
    frames.positions.insert(frames.positions.end(), q.begin(), q.end());
  }
  return frames;
}

void check_player(const PlayerFrames& frames, const PlayerOptions& options) {
  if (!(options.rate > 0) || !std::isfinite(options.rate))
    throw std::invalid_argument("~rate must be a positive number (playback speed), got " +
                                std::to_string(options.rate));
  if (!(options.loop_pause >= 0) || !std::isfinite(options.loop_pause))
    throw std::invalid_argument("~loop_pause must be a number of seconds >= 0, got " +
                                std::to_string(options.loop_pause));
  if (frames.frame_count < 1) throw std::invalid_argument("the recording has no frames");
  if (!(frames.frame_time > 0) || !std::isfinite(frames.frame_time))
    throw std::invalid_argument("the recording's frame time must be positive, got " +
                                std::to_string(frames.frame_time));
  const double period = frames.frame_time / options.rate;
  if (!(period >= kMinPeriod && period <= kMaxPeriod))
    throw std::invalid_argument(
        "a frame time of " + mbk::format_double(frames.frame_time) + " s at ~rate " +
        mbk::format_double(options.rate) + " plays a frame every " + mbk::format_double(period) +
        " s, not between 1e-9 s (a stamp's nanosecond) and 2147483647 s (the longest ROS "
        "duration)");
  if (options.loop_pause > kMaxPeriod)
    throw std::invalid_argument(
        "~loop_pause must be at most 2147483647 s (the longest ROS duration), got " +
        mbk::format_double(options.loop_pause));
}

FramePlayer::FramePlayer(PlayerFrames frames, const PlayerOptions& options)
    : frames_(std::move(frames)),
      period_(frames_.frame_time / options.rate),
      pause_ticks_(static_cast<long>(std::ceil(options.loop_pause / period_))),
      loop_(options.loop) {}

std::optional<ros::Time> FramePlayer::stamp_at(const ros::Time& start, long tick) const {
  const double offset = tick * period_;  // s
  if (!(start.toSec() + offset < kLastStamp)) return std::nullopt;
  ros::Time at;
  at.fromNSec(start.toNSec() + static_cast<uint64_t>(std::llround(offset * 1e9)));
  return at;
}

long FramePlayer::frame_at(long tick) const {
  const long n = frames_.frame_count;
  if (!loop_) return tick < n ? tick : -2;
  const long in_cycle = tick % (n + pause_ticks_);
  return in_cycle < n ? in_cycle : -1;
}

void FramePlayer::fill(long frame, sensor_msgs::JointState& msg) const {
  const size_t width = frames_.names.size();
  msg.name = frames_.names;
  msg.position.assign(frames_.positions.begin() + frame * width,
                      frames_.positions.begin() + (frame + 1) * width);
  msg.velocity.clear();
  msg.effort.clear();
}

}  // namespace mbk_ros
