// A bare YAML scene (doc/conventions.md: `lower_body_array`, with `joint_type`, `frame`, `speeds`
// and no `bodies`) read from yaml-cpp's parser events, not its node tree: the tree takes about
// 2 KB per array entry (a 3.5 MB array of 450,000 entries: 0.9 GB), the events the array's ints.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

// True with `model` set when `text` is a plain bare scene: a map whose `lower_body_array` is a
// list of scalars, whose `frame`, `speeds` and `joint_type` are scalars, without `bodies`,
// anchors, aliases or a key given twice; false for anything else (the node tree reads it, with
// the same results and errors). Throws std::invalid_argument "<line>: <what>" as
// load_yaml_scene_string's, less the source.
bool read_bare_scene(const std::string& text, Model& model);

}  // namespace mbk
