#include "mb_kinematics/ros/outputs/serialized_numbers.h"

#include <cstring>
#include <string>
#include <vector>

namespace mbk_ros {
namespace {

// Messages whose fields are doubles alone: serialized as they lie in memory.
static_assert(sizeof(geometry_msgs::Transform) == 7 * sizeof(double), "Transform: 7 doubles");
static_assert(sizeof(geometry_msgs::Pose) == 7 * sizeof(double), "Pose: 7 doubles");
static_assert(sizeof(geometry_msgs::Twist) == 6 * sizeof(double), "Twist: 6 doubles");
static_assert(sizeof(geometry_msgs::Accel) == 6 * sizeof(double), "Accel: 6 doubles");
static_assert(sizeof(geometry_msgs::Point) == 3 * sizeof(double), "Point: 3 doubles");
static_assert(sizeof(geometry_msgs::Vector3) == 3 * sizeof(double), "Vector3: 3 doubles");

// The image's bytes from `p`, each function moving `p` past what it wrote or skipped.
template <typename T>
void put(uint8_t*& p, const T& value) {
  std::memcpy(p, &value, sizeof value);
  p += sizeof value;
}

// An array's length (uint32) in the image: true if it is `n`.
bool same_length(uint8_t*& p, size_t n) {
  uint32_t length;
  std::memcpy(&length, p, sizeof length);
  p += sizeof length;
  return length == n;
}

// A string: skipped if the image's has its length (its characters are the message's: the
// caller changes strings only through a whole serialization).
bool skip_string(uint8_t*& p, const std::string& s) {
  if (!same_length(p, s.size())) return false;
  p += s.size();
  return true;
}

bool put_header(uint8_t*& p, const std_msgs::Header& h) {
  put(p, h.seq);
  put(p, h.stamp.sec);
  put(p, h.stamp.nsec);
  return skip_string(p, h.frame_id);
}

}  // namespace

bool write_numbers(const tf2_msgs::TFMessage& msg, uint8_t* image, size_t size) {
  uint8_t* p = image;
  const uint8_t* end = image + size;
  if (!same_length(p, msg.transforms.size())) return false;
  for (const geometry_msgs::TransformStamped& t : msg.transforms) {
    if (!put_header(p, t.header) || !skip_string(p, t.child_frame_id)) return false;
    put(p, t.transform);
  }
  return p == end;
}

bool write_numbers(const mb_kinematics_msgs::BodyKinematicsArray& msg, uint8_t* image,
                   size_t size) {
  uint8_t* p = image;
  const uint8_t* end = image + size;
  if (!put_header(p, msg.header) || !same_length(p, msg.bodies.size())) return false;
  for (const mb_kinematics_msgs::BodyKinematics& b : msg.bodies) {
    if (!skip_string(p, b.name)) return false;
    put(p, b.index);
    put(p, b.lower_body);
    put(p, b.pose);
    put(p, b.mass_center);
    put(p, b.twist);
    put(p, b.accel);
  }
  const mb_kinematics_msgs::SystemKinematics& s = msg.system;
  put(p, s.filled);
  put(p, s.mass);
  put(p, s.mass_center);
  put(p, s.velocity);
  put(p, s.acceleration);
  put(p, s.linear_momentum);
  put(p, s.angular_momentum_known);
  put(p, s.angular_momentum);
  if (!same_length(p, s.missing_segments.size())) return false;
  for (const std::string& segment : s.missing_segments)
    if (!skip_string(p, segment)) return false;
  return p == end;
}

}  // namespace mbk_ros
