// bvh_player: a BVH motion capture file's frames as sensor_msgs/JointState on joint_states, one
// message per frame at the file's frame rate times ~rate, looping (doc/node.md#bvh_player).
// Names are the coordinates of the model mb_kinematics_node makes of the same file (the root's
// six included); positions in radians and metres (~scale metres per file unit). Stamps follow
// the ideal schedule start + i * frame_time / ~rate.
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "mb_kinematics/ros/frame_player.h"

namespace {

// ~file, ~scale, ~rate, ~loop and ~loop_pause into a player; throws std::invalid_argument.
mbk_ros::FramePlayer make_player(const ros::NodeHandle& pnh) {
  std::string path;
  if (!pnh.getParam("file", path) || path.empty())
    throw std::invalid_argument("~file (the .bvh file to play) is not set");
  mbk_ros::PlayerOptions options;
  pnh.param("rate", options.rate, options.rate);
  pnh.param("loop", options.loop, options.loop);
  pnh.param("loop_pause", options.loop_pause, options.loop_pause);
  const mbk_ros::PlayerFrames frames = mbk_ros::bvh_player_frames(path, pnh.param("scale", 1.0));
  mbk_ros::check_player(frames, options);
  ROS_INFO_STREAM("bvh_player: " << path << ": " << frames.frame_count << " frames of "
                                 << frames.names.size() << " coordinates at "
                                 << 1 / frames.frame_time << " Hz, played at x" << options.rate
                                 << (options.loop ? ", looping" : ""));
  return mbk_ros::FramePlayer(frames, options);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "bvh_player");
  ros::NodeHandle nh, pnh("~");
  std::unique_ptr<mbk_ros::FramePlayer> player;
  try {
    player = std::make_unique<mbk_ros::FramePlayer>(make_player(pnh));
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("bvh_player: " << e.what());
    return 1;
  }
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  sensor_msgs::JointState msg;
  const ros::Time start = ros::Time::now();
  for (long tick = 0; ros::ok(); ++tick) {
    const std::optional<ros::Time> stamp = player->stamp_at(start, tick);
    if (!stamp) {
      ROS_ERROR("bvh_player: the next frame's stamp is past what a ROS time holds; stopping");
      return 1;
    }
    const ros::Time at = *stamp;
    ros::Time::sleepUntil(at);
    const long frame = player->frame_at(tick);
    if (frame == -2) break;   // the end, without ~loop
    if (frame < 0) continue;  // the pause at a loop
    player->fill(frame, msg);
    msg.header.stamp = at;
    states.publish(msg);
  }
  return 0;
}
