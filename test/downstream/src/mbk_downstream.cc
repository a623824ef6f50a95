// Uses mb_kinematics as an installed package would be used: the core (a bare chain, the
// recursion) and a message of mb_kinematics_msgs. Prints the message's text and exits 0 when the
// mass center of the last body is where a straight chain puts it.
#include <mb_kinematics_msgs/BodyKinematicsArray.h>

#include <iostream>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

int main() {
  const mbk::Model model = mbk::make_bare_model({0, 1, 2}, mbk::JointType::kRevolute);
  const mbk::JointState<double> state(model);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  mb_kinematics_msgs::BodyKinematicsArray msg;
  msg.bodies.resize(model.body_count());
  mb_kinematics_msgs::BodyKinematics& last = msg.bodies.back();
  last.name = model.bodies.back().name;
  last.mass_center.x = data.mass_center.back().x();
  std::cout << last;
  return last.mass_center.x == 2.5 ? 0 : 1;  // offsets of 1 along x, mass centers half way
}
