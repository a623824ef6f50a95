// ~get_partial_velocities (mb_kinematics_msgs/GetPartialVelocities, doc/method.md 9): the partial
// velocity arrays of the named bodies and their time derivatives at the latest sample, sparse
// (the independent speeds of each body's chain, mimic columns folded into their sources').
// Keeps a copy of the latest sample's coordinates and speeds (no allocation per sample). The
// calls are served on a thread of their own (doc/node.md), never in the input's callbacks:
// each takes a copy of that sample under a short lock of its own, then computes the requested
// bodies' chains only (core/chain_partial_velocity.h), so /tf keeps its rate during a long call.
// A request needing more than ~partial_velocities_max_entries columns is refused, naming both.
// A ~reload cancels a call in progress (success false, saying so) rather than wait for it.
#pragma once

#include <mb_kinematics_msgs/GetPartialVelocities.h>
#include <ros/callback_queue.h>
#include <ros/service_server.h>
#include <ros/spinner.h>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include "mb_kinematics/ros/outputs/output.h"

namespace mbk_ros {

class PartialVelocitiesService : public Output {
 public:
  static bool enabled(const NodeParams&) { return true; }
  explicit PartialVelocitiesService(const OutputSetup& setup);
  // Ends the service, waiting for a call in progress (roscpp's CallbackQueue::removeByID): the
  // model it reads (~reload replaces it after this) stays alive until the call has returned.
  ~PartialVelocitiesService() override;
  mbk::Level level() const override { return mbk::Level::kVelocity; }  // the columns need q, y
  bool uses_data() const override { return false; }
  bool active() override { return true; }
  bool is_service() const override { return true; }
  void cancel_calls() override { cancelled_ = true; }
  void publish(const ros::Time& stamp, const Sample& sample) override;

 private:
  using Request = mb_kinematics_msgs::GetPartialVelocities::Request;
  using Response = mb_kinematics_msgs::GetPartialVelocities::Response;

  // The latest sample, as publish() leaves it for the calls.
  struct Latest {
    explicit Latest(const mbk::Model& model) : state(model), published(model.body_count() + 1, 1) {}
    mbk::JointState<double> state;
    std::vector<char> published;  // per body (~missing_coordinates skip)
    ros::Time stamp;
    bool has_sample = false;
  };

  bool answer(Request& request, Response& response);  // on the service's own thread
  // The bodies asked (every published one for none), or "" and the message.
  bool bodies(const Request& request, const Latest& latest, std::vector<int>& out,
              std::string& message) const;
  // Refuses (false, the message) a request of more than the limit's entries.
  bool within_limit(const Request& request, const std::vector<int>& bodies,
                    std::string& message) const;

  const mbk::Model& model_;
  std::string frame_;
  long max_entries_;
  std::vector<long> chain_speeds_;      // per body: the columns a request for it costs
  std::mutex latest_mutex_;             // publish() and the copy a call takes; nothing else
  std::atomic<bool> cancelled_{false};  // by ~reload: calls end with an empty answer
  Latest latest_;
  ros::CallbackQueue queue_;  // the service's callbacks, on spinner_'s thread
  ros::AsyncSpinner spinner_;
  ros::ServiceServer server_;
};

}  // namespace mbk_ros
