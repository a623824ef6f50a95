// The numbers of a message written into the bytes ros::serialization made of an earlier one of
// the same layout (the same array lengths and strings): /tf's and body_kinematics' messages
// change only their numbers from one sample to the next, so their serialized bytes are kept
// (reused_serialization.h) and only the numbers written again, where ros::serialization would
// write every field, string and length anew.
#pragma once

#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <tf2_msgs/TFMessage.h>

#include <cstddef>
#include <cstdint>

namespace mbk_ros {

// `msg`'s fixed-size fields (stamps, sequence numbers, indices, flags, doubles) into `image`,
// the `size` bytes of ros::serialization's serialize(msg) (no length prefix) of a message
// with the same strings. False if an array's length or a string's length differs from the
// image's (then it is partly written): the message must be serialized whole.
bool write_numbers(const tf2_msgs::TFMessage& msg, uint8_t* image, size_t size);
bool write_numbers(const mb_kinematics_msgs::BodyKinematicsArray& msg, uint8_t* image, size_t size);

}  // namespace mbk_ros
