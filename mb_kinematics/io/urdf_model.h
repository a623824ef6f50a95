// URDF (urdfdom) into a Model: R is the root link's frame, every other link is a body,
// numbered breadth-first from the root in the order the URDF file lists its joints (doc/method.md
// 8).
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

// Throws std::invalid_argument with "<source>: <what>" for any error.
Model load_urdf_string(const std::string& xml, const std::string& source = "<robot_description>");
Model load_urdf_file(const std::string& path);

}  // namespace mbk
