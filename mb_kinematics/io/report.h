// Text the `mbk` tool prints: the lower body arrays table and the kinematics as JSON.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"

namespace mbk {

// Table 4.2.1 layout: a row per t with L^t(k), each entry shown until its chain has reached 0
// (the 0 itself shown once). `names` (optional, N entries) adds a legend.
std::string format_lower_body_table(const std::vector<int>& lower,
                                    const std::vector<std::string>& names = {});

// One row per t = 0, 1, ... until a row is all zeros, N comma-separated values each.
std::string format_lower_body_csv(const std::vector<int>& lower);

// The `mbk eval` JSON (README "`mbk`"; doc/method.md 8). Throws std::runtime_error naming the body
// if a value is not finite (nothing is printed then).
std::string format_eval_json(const Model& model, const Data<double>& data);

}  // namespace mbk
