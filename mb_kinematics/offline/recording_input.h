// Any recording `mbk bag` reads (a rosbag's joint states, joint accelerations and base odometry, a
// trajectory CSV, a BVH file's motion) as a Recording, read as mbk bag reads it (the Python
// module's read_recording, doc/python.md).
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/offline/bag_input.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk_offline {

struct RecordingInput {
  mbk::Recording recording;
  BaseOdometry base;  // with topics.base_odometry: the odometry read (else empty)
};

// `path`: a `.bag` (read_bag with `topics`: sensor_msgs/JointState on topics.joint_states, and
// where named mb_kinematics_msgs/JointAccelerations and nav_msgs/Odometry), or what
// mbk::read_recording_file reads (topics.joint_accelerations and base_odometry must be empty).
// Messages that cannot be read are counted in `log` under "unreadable message". Throws
// std::invalid_argument naming the file and what is wrong (as mbk bag, a base odometry topic
// without a usable message).
RecordingInput read_recording_input(const mbk::Model& model, const std::string& path,
                                    double bvh_scale, const BagTopics& topics, mbk::DropLog& log);

}  // namespace mbk_offline
