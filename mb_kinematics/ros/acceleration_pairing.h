// joint_accelerations paired with the joint_states sample of the same stamp, whichever of the
// two arrives first (doc/method.md 8): a sample waits for its accelerations
// until they come or the next sample does; then it goes on with estimated accelerations.
// JointStateInput owns one (joint_state_input.h).
#pragma once

#include <sensor_msgs/JointState.h>

#include <vector>

namespace mbk_ros {

// Accelerations of one joint_accelerations message, by coordinate index.
struct AccelerationSample {
  double stamp = 0;
  std::vector<double> value;  // model.nq entries
  std::vector<char> given;    // 1 where the message named the coordinate
};

class AccelerationPairing {
 public:
  AccelerationPairing() { kept_.reserve(kKept); }

  struct Ready {  // a sample that can be computed now
    sensor_msgs::JointStateConstPtr sample;
    bool unpaired;  // true: its accelerations did not come (they are estimated)
  };

  // A joint_states sample. `pairing`: some joint_accelerations publisher is there. Returns the
  // samples to compute now, oldest first: the pending one (unpaired), then `msg` unless it waits
  // for its own accelerations. The list is this object's, valid until the next add (no
  // allocation per sample).
  const std::vector<Ready>& add(const sensor_msgs::JointStateConstPtr& msg, bool pairing);

  // Where to convert the next joint_accelerations message into (kept only by add_next: a
  // message refused leaves the kept ones as they were).
  AccelerationSample& next() { return next_; }
  // Keeps next(), converted, in place of the oldest kept (their storage swapped: no allocation
  // once kKept messages have come); returns the pending sample it completes, if any (likewise
  // until the next add).
  const std::vector<Ready>& add_next();

  // The kept accelerations of stamp t (seconds), or null.
  const AccelerationSample* at(double t) const;

 private:
  static constexpr size_t kKept = 16;  // the latest few, by stamp
  const AccelerationSample& newest() const {
    return kept_[(oldest_ + kept_.size() - 1) % kept_.size()];
  }

  sensor_msgs::JointStateConstPtr pending_;
  std::vector<AccelerationSample> kept_;  // a ring of at most kKept, oldest at oldest_
  size_t oldest_ = 0;
  AccelerationSample next_;
  std::vector<Ready> ready_;  // what add returns (at most two)
};

}  // namespace mbk_ros
