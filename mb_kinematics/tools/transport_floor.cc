// transport_floor: the node's ROS transport without its computation, for scripts/node_load.sh
// --floor (doc/speed.md "The node's load"). It takes joint_states as mb_kinematics_node does (the
// same immediate callback queue, tcpNoDelay) and, for each message, publishes on /tf and
// body_kinematics messages of the node's shape for robot_description (a transform per moving
// joint, every body with its name), their values left at zero and only their stamps set: what
// roscpp costs the node per sample (receive, serialize, send) when its own work costs nothing.
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>

#include <string>

#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/messages/body_kinematics.h"
#include "mb_kinematics/ros/immediate_callback_queue.h"
#include "mb_kinematics/ros/outputs/output.h"
#include "mb_kinematics/ros/outputs/reused_message.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "transport_floor");
  ros::NodeHandle nh;
  std::string xml;
  if (!nh.getParam("robot_description", xml)) {
    ROS_FATAL("transport_floor: no robot_description");
    return 1;
  }
  const mbk::Model model = mbk::load_urdf_string(xml);
  mbk_ros::ReusedMessage<tf2_msgs::TFMessage> tf;
  mbk_ros::ReusedMessage<mb_kinematics_msgs::BodyKinematicsArray> bodies;
  for (int k = 1; k <= model.body_count(); ++k) {
    if (mbk::coordinate_count(model.bodies[k].joint.type) == 0) continue;
    geometry_msgs::TransformStamped& t = tf.next().transforms.emplace_back();
    const int j = model.bodies[k].lower;
    t.header.frame_id = j ? model.bodies[j].name : model.frame;
    t.child_frame_id = model.bodies[k].name;
  }
  mbk_messages::init_body_kinematics(model, model.frame, bodies.next());
  const ros::Publisher tf_pub = nh.advertise<tf2_msgs::TFMessage>("/tf", mbk_ros::kSampleQueueSize);
  const ros::Publisher bodies_pub = nh.advertise<mb_kinematics_msgs::BodyKinematicsArray>(
      "body_kinematics", mbk_ros::kSampleQueueSize);

  mbk_ros::ImmediateCallbackQueue queue;
  ros::SubscribeOptions options;
  options.init<sensor_msgs::JointState>("joint_states", 1,
                                        [&](const sensor_msgs::JointStateConstPtr& msg) {
                                          if (tf_pub.getNumSubscribers() > 0) {
                                            for (auto& t : tf.next().transforms)
                                              t.header.stamp = msg->header.stamp;
                                            tf.publish(tf_pub);
                                          }
                                          if (bodies_pub.getNumSubscribers() > 0) {
                                            bodies.next().header.stamp = msg->header.stamp;
                                            bodies.publish(bodies_pub);
                                          }
                                        });
  options.transport_hints = ros::TransportHints().tcpNoDelay();
  options.callback_queue = &queue;
  const ros::Subscriber sub = nh.subscribe(options);
  ros::spin();
  return 0;
}
