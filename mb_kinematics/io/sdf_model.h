// SDFormat (Gazebo's model format, 1.4 and later) into a Model, through libsdformat12: frames are
// resolved by its semantic pose API (relative_to, nested models, frames, a joint to the world).
// R is the world when a joint has the world as parent, else the one link no joint moves (as in a
// URDF); every other link is a body of the same name (a nested model's `model::link`), numbered
// breadth-first in the order the file lists the joints. Where a joint's frame is not its child
// link's, a massless body `<link>__<joint>` at the joint frame comes first (doc/conventions.md
// "SDFormat").
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

// Throws std::invalid_argument with "<source>: <what>" for a model sdformat refuses or that does
// not map (naming the joint or link), std::runtime_error naming the Debian package when
// libsdformat12 cannot be opened. sdformat is loaded when the first SDFormat model is read
// (io/sdformat_reader.cc, a library of its own).
Model load_sdf_file(const std::string& path);
Model load_sdf_string(const std::string& xml, const std::string& source = "<text>");

// True when the first element of the XML text is <sdf>.
bool is_sdf_text(const std::string& xml);

}  // namespace mbk
