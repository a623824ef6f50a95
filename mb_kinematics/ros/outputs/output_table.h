// The node's outputs, in publishing order: those its parameters enable.
#pragma once

#include <memory>
#include <vector>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

// `in_r` false: those that need no R (made at start); true: the others, made once R is known
// (with ~base_odometry, at its first message).
std::vector<std::unique_ptr<Output>> make_outputs(const OutputSetup& setup, bool in_r);

}  // namespace mbk_ros
