// The Euler order of each body's joint angles for `mbk bag --angles` (doc/recorded_data.md): one
// order for every body ("ZXY", "312"), or a YAML file of body or joint name: order, with
// `default: ORDER` for the bodies it does not name. ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/euler_order.h"
#include "mb_kinematics/core/model.h"

namespace mbk {

// Per body k = 0..N (index 0, R, unused): `text` an order, or a file name ending in .yaml or
// .yml. Throws std::invalid_argument with one line naming the file, line and what is wrong: not
// YAML, not a map, an unknown body or joint, an unknown order, a body named twice (by its name
// and its joint's), bodies left without an order and no `default`.
std::vector<EulerOrder> angle_orders(const Model& model, const std::string& text);

// The same from the YAML text of `path`.
std::vector<EulerOrder> parse_angle_orders(const Model& model, const std::string& yaml,
                                           const std::string& path);

}  // namespace mbk
