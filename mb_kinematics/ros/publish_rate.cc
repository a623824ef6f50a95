#include "mb_kinematics/ros/publish_rate.h"

namespace mbk_ros {

bool PublishRate::skip(double t) {
  if (frequency_ <= 0) return false;
  const double period = 1.0 / frequency_;
  if (t >= last_output_ && t - last_output_ < period * (1 - 1e-9)) return true;
  last_output_ = t;
  return false;
}

}  // namespace mbk_ros
