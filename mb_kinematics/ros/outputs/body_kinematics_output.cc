#include "mb_kinematics/ros/outputs/body_kinematics_output.h"

#include <mb_kinematics_msgs/LowerBodyArray.h>

namespace mbk_ros {

BodyKinematicsOutput::BodyKinematicsOutput(const OutputSetup& setup)
    : publisher_(setup.nh.advertise<mb_kinematics_msgs::BodyKinematicsArray>("body_kinematics",
                                                                             kSampleQueueSize)),
      shown_(setup.model.body_count() + 1, 1) {
  mbk_messages::init_body_kinematics(setup.model, setup.frame, msg_.reshape(),
                                     setup.missing_segments);
}

void BodyKinematicsOutput::publish(const ros::Time& stamp, const Sample& sample) {
  if (sample.published != shown_) {  // ~missing_coordinates skip: bodies left out or joining
    mbk_messages::select_body_kinematics(sample.model, sample.published, msg_.reshape());
    shown_ = sample.published;
  }
  mb_kinematics_msgs::BodyKinematicsArray& msg = msg_.next();
  mbk_messages::fill_kinematics(stamp, sample.model, sample.data, sample.complete, msg);
  msg_.publish(publisher_);
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
