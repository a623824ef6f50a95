// Reads joint samples from a rosbag with the rosbag C++ API (no replay, no master):
// sensor_msgs/JointState on one topic and, optionally, mb_kinematics_msgs/JointAccelerations on
// another, into a RecordingBuilder.
#pragma once

#include <functional>
#include <string>

#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk_offline {

struct BagTopics {
  std::string joint_states = "/joint_states";
  std::string joint_accelerations;  // empty: none
  std::string base_odometry;        // empty: none (nav_msgs/Odometry)
};

// The base's odometry (the node's semantics, core/floating_base.h): samples in time order (a stamp
// not after the previous one, or NaN/Inf, is dropped and counted) and R's name.
struct BaseOdometry {
  std::vector<mbk::BaseSample> samples;
  std::string frame;  // the odometry's header.frame_id: R
};

// Messages that could not be read (damaged, of another type on the topic): skipped, counted,
// the first one named; reading goes on with the next.
struct Unreadable {
  long count = 0;
  std::string first;
  void add(long n, const std::string& detail) {
    if (count == 0) first = detail;
    count += n;
  }
};

// A topic is found by its name with or without the leading '/' (rosbag record stores relative
// names as given). Throws std::invalid_argument for a bag that cannot be opened (corrupt,
// truncated: unindexed) and for a topic the bag lacks or of another type (naming the topics and
// types it has). A bag that becomes unreadable part way keeps what was read and counts the rest in
// `unreadable`, as it counts every message that cannot be read. `progress(done, total)` is called
// now and then with message counts. With topics.base_odometry, `base` receives the odometry.
// The bag's records are first checked (check_bag_records), then it is read whole in a child
// process (librosbag crashes on some damaged bags);
// `checked`: an earlier read_bag of this run did that already (mbk bag's second pass).
void read_bag(const std::string& path, const BagTopics& topics, mbk::RecordingBuilder& builder,
              BaseOdometry& base, Unreadable& unreadable,
              const std::function<void(long, long)>& progress, bool checked = false);

}  // namespace mbk_offline
