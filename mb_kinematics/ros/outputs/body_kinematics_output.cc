#include "mb_kinematics/ros/outputs/body_kinematics_output.h"

#include <mb_kinematics_msgs/LowerBodyArray.h>

#include "mb_kinematics/ros/outputs/message_fields.h"
#include "mb_kinematics/ros/outputs/system_fields.h"

namespace mbk_ros {

void init_body_kinematics(const mbk::Model& model, const std::string& frame,
                          mb_kinematics_msgs::BodyKinematicsArray& msg) {
  msg.header.frame_id = frame;
  msg.bodies.resize(model.body_count());
  for (int k = 1; k <= model.body_count(); ++k) {
    auto& b = msg.bodies[k - 1];
    b.name = model.bodies[k].name;
    b.index = k;
    b.lower_body = model.bodies[k].lower;
  }
}

void fill_body_kinematics(const ros::Time& stamp, const mbk::Data<double>& data,
                          mb_kinematics_msgs::BodyKinematicsArray& msg) {
  msg.header.stamp = stamp;
  for (size_t i = 0; i < msg.bodies.size(); ++i) {
    const size_t k = i + 1;
    auto& b = msg.bodies[i];
    set_vector(data.origin[k], b.pose.position);
    set_quaternion(data.rotation[k], b.pose.orientation);
    set_vector(data.mass_center[k], b.mass_center);
    set_vector(data.omega[k], b.twist.angular);
    set_vector(data.mass_center_velocity[k], b.twist.linear);
    set_vector(data.alpha[k], b.accel.angular);
    set_vector(data.mass_center_acceleration[k], b.accel.linear);
  }
}

BodyKinematicsOutput::BodyKinematicsOutput(const OutputSetup& setup)
    : publisher_(
          setup.nh.advertise<mb_kinematics_msgs::BodyKinematicsArray>("body_kinematics", 10)) {
  init_body_kinematics(setup.model, setup.frame, msg_);
}

void BodyKinematicsOutput::publish(const ros::Time& stamp, const Sample& sample) {
  fill_body_kinematics(stamp, sample.data, msg_);
  fill_system_kinematics(sample.model, sample.data, msg_.system);  // issue 10
  publisher_.publish(msg_);
}

LowerBodyArrayOutput::LowerBodyArrayOutput(const OutputSetup& setup)
    : publisher_(
          setup.nh.advertise<mb_kinematics_msgs::LowerBodyArray>("lower_body_array", 1, true)) {
  mb_kinematics_msgs::LowerBodyArray topology;
  topology.header.stamp = ros::Time::now();
  topology.header.frame_id = setup.frame;
  for (int k = 1; k <= setup.model.body_count(); ++k) {
    topology.names.push_back(setup.model.bodies[k].name);
    topology.lower.push_back(setup.model.bodies[k].lower);
  }
  publisher_.publish(topology);
}

}  // namespace mbk_ros
