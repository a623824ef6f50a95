// One entry point for model files: `.urdf` through urdfdom, `.sdf` through sdformat (sdf_model.h),
// `.xml` by its first element (MJCF <mujoco> through MuJoCo, mjcf_model.h; SDFormat <sdf>; else
// URDF), `.yaml`/`.yml` scenes, `.bvh` motion capture (its skeleton; bvh_model.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/bvh_model.h"

namespace mbk {

// A model file read once, with what else its text gives.
struct ModelFile {
  Model model;
  // The segments of the body the model lacks (bvh_missing_segments; empty for any file but a BVH
  // skeleton with a body mass): mbk bag's CSV names its whole-body rows "system_incomplete" then,
  // the bag's and the node's body_kinematics list them in system.missing_segments, mbk eval's
  // JSON in "incomplete".
  std::vector<std::string> missing_segments;
  std::optional<BvhFile> bvh;  // a BVH file as parsed, its motion included; empty for the others
};

// Throws std::invalid_argument naming the file and what is wrong. `bvh` applies to BVH files.
ModelFile read_model_file(const std::string& path, const BvhModelOptions& bvh = {});

// read_model_file's model.
Model load_model_file(const std::string& path, const BvhModelOptions& bvh = {});

// True for a file name load_model_file reads as BVH (`.bvh`, any case).
bool is_bvh_file(const std::string& path);

// A model in XML text by its first element: MJCF (<mujoco>), SDFormat (<sdf>), else URDF.
Model load_xml_string(const std::string& xml, const std::string& source);

// A model given as text rather than a file name: its first non-blank character is '<' (URDF,
// MJCF or SDFormat XML, e.g. the robot_description parameter) or it has a line break (a YAML scene).
bool is_model_text(const std::string& path_or_text);

// The model of a file name (load_model_file) or of a text (is_model_text: load_mjcf_string,
// load_sdf_string, load_urdf_string or load_yaml_scene_string, with `source` in the messages). `bvh` applies to a .bvh file only:
// given for anything else, std::invalid_argument.
Model load_model(const std::string& path_or_text, const BvhModelOptions* bvh = nullptr,
                 const std::string& source = "<text>");

}  // namespace mbk
