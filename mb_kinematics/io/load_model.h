// One entry point for model files: `.urdf`/`.xml` through urdfdom, `.yaml`/`.yml` scenes, `.bvh`
// motion capture (its skeleton; bvh_model.h).
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/bvh_model.h"

namespace mbk {

// Throws std::invalid_argument naming the file and what is wrong. `bvh` applies to BVH files.
Model load_model_file(const std::string& path, const BvhModelOptions& bvh = {});

// True for a file name load_model_file reads as BVH (`.bvh`, any case).
bool is_bvh_file(const std::string& path);

}  // namespace mbk
