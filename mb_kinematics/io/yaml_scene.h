// YAML scene files (config/*.yaml) into a Model. The format is documented in doc/conventions.md.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

// Throws std::invalid_argument with "<source>:<line>: <what>" for any error.
Model load_yaml_scene_file(const std::string& path);
Model load_yaml_scene_string(const std::string& text, const std::string& source = "<string>");

}  // namespace mbk
