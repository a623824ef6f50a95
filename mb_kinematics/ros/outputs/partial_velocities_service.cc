#include "mb_kinematics/ros/outputs/partial_velocities_service.h"

#include <ros/advertise_service_options.h>

#include <algorithm>

#include "mb_kinematics/core/chain_partial_velocity.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_ros {
using mbk_messages::set_vector;
namespace {

geometry_msgs::Vector3 vector3(const mbk::Vec3<double>& v) {
  geometry_msgs::Vector3 out;
  set_vector(v, out);
  return out;
}

constexpr char kCancelled[] = "cancelled: the node is reloading its model (~reload); call again";

// Body k's columns into `out`; false if one is not finite.
bool fill_body(const mbk::Model& model, int k, const std::vector<mbk::SpeedColumn>& columns,
               mb_kinematics_msgs::BodyPartialVelocities& out) {
  out.body = model.bodies[k].name;
  for (const mbk::SpeedColumn& c : columns) {
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
      frame_(setup.frame),
      max_entries_(setup.params.partial_velocities_max_entries),
      chain_speeds_(mbk::chain_speed_counts(setup.model)),
      latest_(setup.model),
      spinner_(1, &queue_) {
  ros::AdvertiseServiceOptions options;
  options.init<Request, Response>("get_partial_velocities",
                                  [this](Request& q, Response& r) { return answer(q, r); });
  options.callback_queue = &queue_;
  server_ = setup.pnh.advertiseService(options);
  spinner_.start();
}

PartialVelocitiesService::~PartialVelocitiesService() {
  server_.shutdown();  // waits for a call in progress
  spinner_.stop();
}

void PartialVelocitiesService::publish(const ros::Time& stamp, const Sample& sample) {
  std::lock_guard<std::mutex> lock(latest_mutex_);
  const mbk::VecX<double>&q = sample.state.position, &y = sample.state.velocity;
  std::copy(q.data(), q.data() + q.size(), latest_.state.position.data());  // one memmove each
  std::copy(y.data(), y.data() + y.size(), latest_.state.velocity.data());
  latest_.published = sample.published;  // same size: no allocation
  latest_.stamp = stamp;
  latest_.has_sample = true;
}

bool PartialVelocitiesService::bodies(const Request& request, const Latest& latest,
                                      std::vector<int>& out, std::string& message) const {
  for (const std::string& name : request.bodies) {
    const int k = model_.body_index(name);
    if (k < 1) {
      message = "unknown body '" + name + "'";
      return false;
    }
    if (!latest.published[k]) {
      message = "body '" + name +
                "' is left out: a joint on its chain has never been received, or is "
                "stale (~missing_coordinates)";
      return false;
    }
    out.push_back(k);
  }
  if (request.bodies.empty())  // every body published
    for (int k = 1; k <= model_.body_count(); ++k)
      if (latest.published[k]) out.push_back(k);
  return true;
}

bool PartialVelocitiesService::within_limit(const Request& request, const std::vector<int>& bodies,
                                            std::string& message) const {
  long entries = 0;
  for (int k : bodies) entries += chain_speeds_[k];
  if (entries <= max_entries_) return true;
  message = "refused: " + std::to_string(bodies.size()) +
            (request.bodies.empty() ? " bodies (every body)" : " bodies") + " need " +
            std::to_string(entries) +
            " entries (speed columns, about 100 bytes each), more than "
            "~partial_velocities_max_entries = " +
            std::to_string(max_entries_) + "; ask for fewer bodies or raise the limit";
  return false;
}

bool PartialVelocitiesService::answer(Request& request, Response& response) {
  if (cancelled_) {
    response.message = kCancelled;
    return true;
  }
  Latest latest(model_);
  {
    std::lock_guard<std::mutex> lock(latest_mutex_);  // a copy: the outputs go on meanwhile
    latest = latest_;
  }
  response.header.stamp = latest.stamp;
  response.header.frame_id = frame_;
  std::vector<int> asked;
  if (!latest.has_sample) {
    response.message = "no joint sample with velocities yet";
    return true;
  }
  if (!bodies(request, latest, asked, response.message) ||
      !within_limit(request, asked, response.message))
    return true;
  const auto columns = mbk::chain_partial_velocities(model_, latest.state, asked);
  for (size_t i = 0; i < asked.size(); ++i) {
    if (cancelled_) {
      response.partials.clear();
      response.message = kCancelled;
      return true;
    }
    response.partials.emplace_back();
    if (!fill_body(model_, asked[i], columns[i], response.partials.back())) {
      response.partials.clear();
      response.message =
          "body '" + model_.bodies[asked[i]].name + "': partial velocities not finite";
      return true;
    }
  }
  response.success = true;
  return true;
}

}  // namespace mbk_ros
