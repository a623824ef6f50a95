// One output of the node (a topic, a family of topics or a service): its parameter flag (a
// static enabled(const NodeParams&)), what it needs computed, whether anybody listens, and how it
// publishes a sample. KinematicsNode keeps only input (node_input.h), pairing and dispatch; the
// outputs it runs are listed in output_table.cc (adding a topic: a new Output and one line there).
#pragma once

#include <ros/node_handle.h>
#include <ros/time.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/messages/frames.h"
#include "mb_kinematics/ros/coordinate_coverage.h"
#include "mb_kinematics/ros/input_tally.h"
#include "mb_kinematics/ros/node_params.h"

namespace mbk_ros {

// The publisher queue of a topic published per sample: a consumer that stalls for up to 0.1 s at
// 1 kHz misses nothing (as tf2_ros's /tf; doc/speed.md "The node's load").
constexpr uint32_t kSampleQueueSize = 100;

// What an output may use when it is made: it advertises its topics here.
struct OutputSetup {
  ros::NodeHandle& nh;
  ros::NodeHandle& pnh;  // the node's private handle
  const NodeParams& params;
  const mbk::Model& model;
  const std::vector<std::string>& missing_segments;  // of the model's body (load_node_model)
  const std::string& frame;  // R (with ~frame_prefix when it is the model's own); "" before it
  // The input's fate and what is missing (node_input.h), for /diagnostics.
  InputTally& tally;
  const CoordinateCoverage& coverage;
  // Held while the node takes in and publishes a sample (in roscpp's network thread:
  // immediate_callback_queue.h): an output's own callbacks (a service, a timer) lock it too.
  std::mutex& mutex;
  // The tf frames of the bodies (~frame_prefix) and R.
  mbk_messages::FrameNames frames() const { return {model, params.frame_prefix, frame}; }
};

// One computed sample.
struct Sample {
  const mbk::Model& model;
  const mbk::JointState<double>& state;  // checked by mbk::check_state
  const mbk::Data<double>& data;         // forward_kinematics up to `level`, if uses_data()
  mbk::Level level;                      // what the state holds: estimates may lag behind
  // Per body (index k; [0] is R): published with this sample. ~missing_coordinates skip leaves
  // out the bodies whose chain lacks a coordinate; `complete`: none is left out.
  const std::vector<char>& published;
  bool complete;
};

class Output {
 public:
  virtual ~Output() = default;
  // The computation it needs: publish() is called only for samples of at least this level.
  virtual mbk::Level level() const = 0;
  // False if it reads the joint state only (then no forward_kinematics is run for it).
  virtual bool uses_data() const { return true; }
  // True if it advertises a service: a node advertises one name once, so ~reload ends the old
  // one before making the new (topics: the other way round, so that subscribers stay connected).
  virtual bool is_service() const { return false; }
  // A service: end the calls in progress at once and refuse new ones (~reload is about to end
  // it, and waits for its calls meanwhile, holding the input: in a nodelet, the manager's
  // network thread and its bond).
  virtual void cancel_calls() {}
  // Whether anybody listens now; asked once per sample, before the computation.
  virtual bool active() = 0;
  // Called after active() returned true, when the sample reached level().
  virtual void publish(const ros::Time& stamp, const Sample& sample) = 0;
};

}  // namespace mbk_ros
