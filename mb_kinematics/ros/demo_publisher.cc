// demo_publisher: smooth, known joint trajectories for any model the node can load (same
// parameters: robot_description, ~model, ~lower_body_array), on joint_states with velocities,
// and their exact accelerations on joint_accelerations with the same stamp (published first).
// Every coordinate i (mimics aside) follows q_i(t) = b_i + a_i sin(w_i t + p_i).
#include <mb_kinematics_msgs/JointAccelerations.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <exception>
#include <vector>

#include "mb_kinematics/ros/kinematics_node.h"

namespace {

struct Wave {
  double b, a, w, p;
};

// Amplitudes by coordinate kind: 0.05 m for translations, 0.4 rad for angles, Euler parameters
// about the identity (e4 = 1 + ...; rotations use e / |e|).
std::vector<Wave> make_waves(const mbk::Model& model) {
  std::vector<Wave> waves(model.nq);
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& body = model.bodies[k];
    const auto& suffixes = mbk::coordinate_suffixes(body.joint.type);
    for (size_t c = 0; c < suffixes.size(); ++c) {
      const int i = body.q_index + static_cast<int>(c);
      const std::string& s = suffixes[c];
      const bool translation =
          body.joint.type == mbk::JointType::kPrismatic || s == "x" || s == "y" || s == "z";
      const bool euler = s.size() == 2 && s[0] == 'e';
      Wave& w = waves[i];
      w.b = s == "e4" ? 1.0 : 0.0;
      w.a = translation ? 0.05 : euler ? 0.2 : 0.4;
      w.w = 2 * M_PI * (0.2 + 0.4 * std::fmod(0.618034 * (i + 1), 1.0));
      w.p = 0.7 * i;
    }
  }
  return waves;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_publisher");
  ros::NodeHandle nh, pnh("~");
  mbk::Model model;
  try {
    model = mbk_ros::load_node_model(mbk_ros::read_node_params(nh, pnh));
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("demo_publisher: " << e.what());
    return 1;
  }
  const double rate = pnh.param("rate", 50.0);
  const bool velocities = pnh.param("publish_velocities", true);
  const bool accelerations = pnh.param("publish_accelerations", true);
  const std::vector<Wave> waves = make_waves(model);
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
      const Wave& w = waves[i];
      const double phase = w.w * t + w.p;
      js.position.push_back(w.b + w.a * std::sin(phase));
      if (velocities) js.velocity.push_back(w.a * w.w * std::cos(phase));
      ja.acceleration.push_back(-w.a * w.w * w.w * std::sin(phase));
    }
    if (accelerations) accels.publish(ja);
    states.publish(js);
    ros::spinOnce();
    loop.sleep();
  }
  return 0;
}
