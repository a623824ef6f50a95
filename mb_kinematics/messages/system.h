// The `system` field of body_kinematics (mb_kinematics_msgs/SystemKinematics, doc/method.md 9):
// total mass, system mass center and its motion, linear momentum, and the angular momentum about G
// when every body with mass has an inertia, and the segments of the body the model lacks. Filled
// by fill_kinematics (body_kinematics.h), for the node while body_kinematics has a subscriber and
// for mbk bag's output bag.
#pragma once

#include <mb_kinematics_msgs/SystemKinematics.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"

namespace mbk_messages {

// From a Data at Level kAcceleration. `filled` is false for a model of total mass 0 (no mass
// center); angular_momentum_known false leaves angular_momentum zero. missing_segments, a
// property of the model, stays as init_body_kinematics set it. No allocation.
void fill_system_kinematics(const mbk::Model& model, const mbk::Data<double>& data,
                            mb_kinematics_msgs::SystemKinematics& msg);

// Not filled (a sample over a subset of the bodies): every field zero or false but
// missing_segments. No allocation.
void clear_system_kinematics(mb_kinematics_msgs::SystemKinematics& msg);

}  // namespace mbk_messages
