// The node's outputs, in publishing order: those its parameters enable.
#pragma once

#include <memory>
#include <vector>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

std::vector<std::unique_ptr<Output>> make_outputs(const OutputSetup& setup);

}  // namespace mbk_ros
