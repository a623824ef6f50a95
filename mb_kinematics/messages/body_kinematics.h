// body_kinematics (mb_kinematics_msgs/BodyKinematicsArray) from the core's Data: every body's
// pose, mass center, twist (omega_k, velocity of G_k) and accel (alpha_k, acceleration of G_k),
// all in R, and the system's: the node and `mbk bag` fill it the same way.
#pragma once

#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <ros/time.h>

#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/messages/fields.h"
#include "mb_kinematics/messages/system.h"

namespace mbk_messages {

// Names, indices and lower bodies of `msg`, once, and system.missing_segments: the segments of
// the body that the model lacks (mbk::ModelFile::missing_segments: a BVH skeleton's, e.g. "left
// hand"; none for a URDF or YAML model). The per-sample fill leaves them.
inline void init_body_kinematics(const mbk::Model& model, const std::string& frame,
                                 mb_kinematics_msgs::BodyKinematicsArray& msg,
                                 const std::vector<std::string>& missing_segments = {}) {
  msg.header.frame_id = frame;
  msg.system.missing_segments = missing_segments;
  msg.bodies.resize(model.body_count());
  for (int k = 1; k <= model.body_count(); ++k) {
    auto& b = msg.bodies[k - 1];
    b.name = model.bodies[k].name;
    b.index = k;
    b.lower_body = model.bodies[k].lower;
  }
}

// Only the bodies k with published[k] (N + 1 entries), in body order: the node's
// ~missing_coordinates skip leaves out the bodies whose chain lacks a coordinate.
inline void select_body_kinematics(const mbk::Model& model, const std::vector<char>& published,
                                   mb_kinematics_msgs::BodyKinematicsArray& msg) {
  msg.bodies.clear();
  for (int k = 1; k <= model.body_count(); ++k) {
    if (!published[k]) continue;
    msg.bodies.emplace_back();
    msg.bodies.back().name = model.bodies[k].name;
    msg.bodies.back().index = k;
    msg.bodies.back().lower_body = model.bodies[k].lower;
  }
}

// The sample's values (forward_kinematics at Level kAcceleration) into `msg`'s bodies (each
// by its index k). The arrays' starts are read once (the compiler would read them again after
// each store into the message, which might change them for all it knows) and each vector is
// copied whole (copy_vector: two moves instead of three).
inline void fill_body_kinematics(const ros::Time& stamp, const mbk::Data<double>& data,
                                 mb_kinematics_msgs::BodyKinematicsArray& msg) {
  msg.header.stamp = stamp;
  const mbk::Mat3<double>* rotation = data.rotation.data();
  const mbk::Vec3<double>*origin = data.origin.data(), *mass_center = data.mass_center.data(),
        *omega = data.omega.data(), *velocity = data.mass_center_velocity.data(),
        *alpha = data.alpha.data(), *acceleration = data.mass_center_acceleration.data();
  for (auto& b : msg.bodies) {
    const size_t k = b.index;
    copy_vector(origin[k], b.pose.position);
    set_quaternion(rotation[k], b.pose.orientation);
    copy_vector(mass_center[k], b.mass_center);
    copy_vector(omega[k], b.twist.angular);
    copy_vector(velocity[k], b.twist.linear);
    copy_vector(alpha[k], b.accel.angular);
    copy_vector(acceleration[k], b.accel.linear);
  }
}

// One sample's body_kinematics: the bodies' values and, when the message holds every body
// (`complete`), the system's (doc/method.md 9); over a subset of the bodies it would pass for
// the system's, so then `system` is left unfilled. No allocation.
inline void fill_kinematics(const ros::Time& stamp, const mbk::Model& model,
                            const mbk::Data<double>& data, bool complete,
                            mb_kinematics_msgs::BodyKinematicsArray& msg) {
  fill_body_kinematics(stamp, data, msg);
  if (complete)
    fill_system_kinematics(model, data, msg.system);
  else
    clear_system_kinematics(msg.system);
}

}  // namespace mbk_messages
