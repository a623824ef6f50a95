#include "mb_kinematics/ros/acceleration_pairing.h"

#include <utility>

namespace mbk_ros {

const std::vector<AccelerationPairing::Ready>& AccelerationPairing::add(
    const sensor_msgs::JointStateConstPtr& msg, bool pairing) {
  ready_.clear();
  if (pending_) {  // its accelerations did not come in time: estimate them
    ready_.push_back({pending_, true});
    pending_.reset();
  }
  if (pairing && !at(msg->header.stamp.toSec()))
    pending_ = msg;  // wait for joint_accelerations of the same stamp (or the next sample)
  else
    ready_.push_back({msg, false});
  return ready_;
}

const std::vector<AccelerationPairing::Ready>& AccelerationPairing::add_next() {
  if (!kept_.empty() && next_.stamp < newest().stamp) {  // stamps went backwards (a bag looping)
    kept_.clear();
    oldest_ = 0;
  }
  if (kept_.size() < kKept) {
    kept_.push_back(std::move(next_));
  } else {
    std::swap(kept_[oldest_], next_);
    oldest_ = (oldest_ + 1) % kKept;
  }
  ready_.clear();
  if (pending_ && pending_->header.stamp.toSec() == newest().stamp) {
    ready_.push_back({pending_, false});
    pending_.reset();
  }
  return ready_;
}

const AccelerationSample* AccelerationPairing::at(double t) const {
  for (const AccelerationSample& a : kept_)
    if (a.stamp == t) return &a;
  return nullptr;
}

}  // namespace mbk_ros
