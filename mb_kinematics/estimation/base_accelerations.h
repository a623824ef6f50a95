// The floating base's accelerations from its odometry (core/floating_base.h): the offline
// estimator over the twist turned into R.
#pragma once

#include <vector>

#include "mb_kinematics/core/floating_base.h"
#include "mb_kinematics/estimation/offline_estimator.h"

namespace mbk {

// The base's accelerations in R at every sample (`samples` in increasing time): the offline
// estimator's first derivatives of the R-component velocities and angular velocities. Samples
// in runs too short for an estimate get zeros and `valid` 0.
void base_accelerations(const std::vector<BaseSample>& samples, const OfflineEstimator& estimator,
                        double max_gap, std::vector<Vec3<double>>& linear_acceleration,
                        std::vector<Vec3<double>>& angular_acceleration, std::vector<int>& valid);

}  // namespace mbk
