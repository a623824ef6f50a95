// `mbk bag`'s error bars in one line: the noise level over the coordinates and the worst error
// bar, for the short summary (the per-coordinate table is --verbose's). ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/offline/offline_kinematics.h"

namespace mbk {

// "  noise level 1.2e-05 (median over 96 coordinates; largest 3.4e-04, Hips/x); worst error
// bar: LeftHand/alpha, acceleration 2.1e+00 (velocity 3.1e-02)\n", or "" without error bars.
// The worst is the coordinate with the largest acceleration standard error.
std::string error_bar_line(const std::vector<CoordinateError>& errors);

// The noise level of that line: the median of the coordinates' noise (errors not empty).
double median_noise(const std::vector<CoordinateError>& errors);

}  // namespace mbk
