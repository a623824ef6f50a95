#include "mb_kinematics/ros/outputs/partial_velocities_service.h"

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_ros {
using mbk_messages::set_vector;
namespace {

geometry_msgs::Vector3 vector3(const mbk::Vec3<double>& v) {
  geometry_msgs::Vector3 out;
  set_vector(v, out);
  return out;
}

// Body k's columns (core/independent_speeds.h) into `out`; false if one is not finite.
bool fill_body(const mbk::Model& model, const mbk::PartialVelocities<double>& pv, int k,
               mb_kinematics_msgs::BodyPartialVelocities& out) {
  out.body = model.bodies[k].name;
  for (const mbk::SpeedColumn& c : mbk::independent_columns(model, pv, k)) {
    if (!(c.omega.allFinite() && c.velocity.allFinite() && c.omega_dot.allFinite() &&
          c.velocity_dot.allFinite()))
      return false;
    out.speeds.push_back(model.speed_names[c.speed]);
    out.partial_omega.push_back(vector3(c.omega));
    out.partial_velocity.push_back(vector3(c.velocity));
    out.partial_omega_dot.push_back(vector3(c.omega_dot));
    out.partial_velocity_dot.push_back(vector3(c.velocity_dot));
  }
  return true;
}

}  // namespace

PartialVelocitiesService::PartialVelocitiesService(const OutputSetup& setup)
    : model_(setup.model),
      mutex_(setup.mutex),
      frame_(setup.frame),
      latest_(setup.model),
      published_(setup.model.body_count() + 1, 1) {
  server_ =
      setup.pnh.advertiseService("get_partial_velocities", &PartialVelocitiesService::answer, this);
}

void PartialVelocitiesService::publish(const ros::Time& stamp, const Sample& sample) {
  latest_.position = sample.state.position;  // same sizes: no allocation
  latest_.velocity = sample.state.velocity;
  published_ = sample.published;  // same size: no allocation
  stamp_ = stamp;
  has_sample_ = true;
}

bool PartialVelocitiesService::answer(
    mb_kinematics_msgs::GetPartialVelocities::Request& request,
    mb_kinematics_msgs::GetPartialVelocities::Response& response) {
  std::lock_guard<std::mutex> lock(mutex_);
  response.header.stamp = stamp_;
  response.header.frame_id = frame_;
  if (!has_sample_) {
    response.message = "no joint sample with velocities yet";
    return true;
  }
  std::vector<int> bodies;
  for (const std::string& name : request.bodies) {
    const int k = model_.body_index(name);
    if (k < 1) {
      response.message = "unknown body '" + name + "'";
      return true;
    }
    if (!published_[k]) {
      response.message = "body '" + name +
                         "' is left out: a joint on its chain has never been received, or is "
                         "stale (~missing_coordinates)";
      return true;
    }
    bodies.push_back(k);
  }
  if (request.bodies.empty())  // every body published
    for (int k = 1; k <= model_.body_count(); ++k)
      if (published_[k]) bodies.push_back(k);
  mbk::PartialVelocities<double> pv(model_);
  mbk::Data<double> data(model_);
  mbk::partial_velocity_kinematics(model_, latest_, pv, data);  // the _dot columns need q, y
  for (int k : bodies) {
    response.partials.emplace_back();
    if (!fill_body(model_, pv, k, response.partials.back())) {
      response.partials.clear();
      response.message = "body '" + model_.bodies[k].name + "': partial velocities not finite";
      return true;
    }
  }
  response.success = true;
  return true;
}

}  // namespace mbk_ros
