// One entry point for model files: `.urdf`/`.xml` through urdfdom, `.yaml`/`.yml` scenes.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

// Throws std::invalid_argument naming the file and what is wrong.
Model load_model_file(const std::string& path);

}  // namespace mbk
