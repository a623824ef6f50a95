// Any recording `mbk bag` reads (a rosbag's joint states, a trajectory CSV, a BVH file's motion)
// as a Recording, read as mbk bag reads it (the Python module's read_recording, doc/python.md).
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/offline/recording.h"

namespace mbk_offline {

// `path`: a `.bag` (sensor_msgs/JointState on `joint_states`), or what
// mbk::read_recording_file reads. Messages that cannot be read are counted in `log` under
// "unreadable message". Throws std::invalid_argument naming the file and what is wrong.
mbk::Recording read_recording_input(const mbk::Model& model, const std::string& path,
                                    double bvh_scale, const std::string& joint_states,
                                    mbk::DropLog& log);

}  // namespace mbk_offline
