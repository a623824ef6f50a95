// MJCF (MuJoCo's model format) into a Model, through MuJoCo's own compiler (mj_loadXML): R is
// MuJoCo's world body; every MJCF body keeps its name, frame and mass; bodies are numbered in
// MuJoCo's order (depth-first, as the file lists them). A body on several joints gets a massless
// body per joint before it, `<body>__<joint>`, one where a joint's anchor is off its frame too
// (doc/conventions.md "MJCF").
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

// Throws std::invalid_argument with "<source>: <what>" for a model MuJoCo refuses or that does
// not map, std::runtime_error naming the Debian package when libmujoco cannot be opened.
Model load_mjcf_file(const std::string& path);
Model load_mjcf_string(const std::string& xml, const std::string& source = "<text>");

// True when the first element of the XML text is <mujoco>.
bool is_mjcf_text(const std::string& xml);

}  // namespace mbk
