#include "mb_kinematics/messages/system.h"

#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_messages {

void fill_system_kinematics(const mbk::Model& model, const mbk::Data<double>& data,
                            mb_kinematics_msgs::SystemKinematics& msg) {
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model, data, s);
  msg.filled = s.mass > 0;
  msg.mass = s.mass;
  set_vector(s.mass_center, msg.mass_center);
  set_vector(s.velocity, msg.velocity);
  set_vector(s.acceleration, msg.acceleration);
  set_vector(s.linear_momentum, msg.linear_momentum);
  msg.angular_momentum_known = msg.filled && s.angular_momentum_known;
  set_vector(s.angular_momentum, msg.angular_momentum);
}

void clear_system_kinematics(mb_kinematics_msgs::SystemKinematics& msg) {
  std::vector<std::string> missing_segments;
  missing_segments.swap(msg.missing_segments);
  msg = mb_kinematics_msgs::SystemKinematics();
  msg.missing_segments.swap(missing_segments);
}

}  // namespace mbk_messages
