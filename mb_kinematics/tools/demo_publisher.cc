// demo_publisher: smooth, known joint trajectories for any model the node can load (same
// parameters: robot_description, ~model, ~lower_body_array), on joint_states with velocities,
// and their exact accelerations on joint_accelerations with the same stamp (published first).
// Every coordinate i (mimics aside) follows q_i(t) = b_i + a_i sin(w_i t + p_i)
// (mb_kinematics/analysis/demo_trajectory.h).
#include <mb_kinematics_msgs/JointAccelerations.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <exception>
#include <vector>

#include "mb_kinematics/analysis/demo_trajectory.h"
#include "mb_kinematics/ros/node_params.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_publisher");
  ros::NodeHandle nh, pnh("~");
  mbk::Model model;
  try {
    model = mbk_ros::load_node_model(mbk_ros::read_node_params(nh, pnh)).model;
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("demo_publisher: " << e.what());
    return 1;
  }
  const double rate = pnh.param("rate", 50.0);
  const bool velocities = pnh.param("publish_velocities", true);
  const bool accelerations = pnh.param("publish_accelerations", true);
  const std::vector<mbk::Wave> waves = mbk::demo_waves(model);
  std::vector<char> mimic(model.nq, 0);
  for (const mbk::Mimic& m : model.mimics) mimic[m.coordinate] = 1;

  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  ros::Publisher accels = accelerations ? nh.advertise<mb_kinematics_msgs::JointAccelerations>(
                                              "joint_accelerations", 10)
                                        : ros::Publisher();
  sensor_msgs::JointState js;
  mb_kinematics_msgs::JointAccelerations ja;
  for (int i = 0; i < model.nq; ++i)
    if (!mimic[i]) js.name.push_back(model.coordinate_names[i]);
  ja.name = js.name;
  const ros::Time start = ros::Time::now();
  ros::Rate loop(rate);
  while (ros::ok()) {
    const ros::Time now = ros::Time::now();
    const double t = (now - start).toSec();
    js.header.stamp = ja.header.stamp = now;
    js.position.clear();
    js.velocity.clear();
    ja.acceleration.clear();
    for (int i = 0; i < model.nq; ++i) {
      if (mimic[i]) continue;
      js.position.push_back(waves[i].at(t, 0));
      if (velocities) js.velocity.push_back(waves[i].at(t, 1));
      ja.acceleration.push_back(waves[i].at(t, 2));
    }
    if (accelerations) accels.publish(ja);
    states.publish(js);
    ros::spinOnce();
    loop.sleep();
  }
  return 0;
}
