// The node's input side (doc/node.md): the model as the source gives it and as the
// kinematics use it (with ~base_odometry, a base body on its own joint: BaseOdometryInput::split),
// joint_states merged and paired with joint_accelerations (JointStateInput), what
// ~missing_coordinates makes of the coordinates missing (CoordinateCoverage), the base's
// odometry, R, and the tally of what went wrong (InputTally: warnings and /diagnostics). Per
// sample it gives a checked state of the kinematics model, or says why not.
#pragma once

#include <mb_kinematics_msgs/JointAccelerations.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/ros/base_odometry_input.h"
#include "mb_kinematics/ros/coordinate_coverage.h"
#include "mb_kinematics/ros/input_tally.h"
#include "mb_kinematics/ros/joint_state_input.h"
#include "mb_kinematics/ros/node_params.h"

namespace mbk_ros {

class NodeInput {
 public:
  using Ready = JointStateInput::Ready;

  // `params` must outlive this object; `odometry_topic`: ~base_odometry resolved. Throws
  // std::invalid_argument for an ~acceleration_estimator with latency.
  NodeInput(const NodeParams& params, const std::string& odometry_topic);
  NodeInput(const NodeInput&) = delete;
  NodeInput& operator=(const NodeInput&) = delete;

  // Everything that depends on the model, made anew (at start and by ~reload): the estimators
  // and the pairing start empty, the tally from zero; R stays once the odometry gave it.
  void load(const mbk::Model& loaded);

  const mbk::Model& loaded() const { return loaded_; }  // as the model source gives it
  const mbk::Model& model() const { return *model_; }   // the kinematics' (with the base)
  const std::string& frame() const { return frame_; }   // R; with ~base_odometry "" until known
  const CoordinateCoverage& coverage() const { return *coverage_; }
  InputTally& tally() { return tally_; }

  // The pairing (JointStateInput::pair): the samples to compute now, oldest first.
  const std::vector<Ready>& pair(const sensor_msgs::JointStateConstPtr& msg, bool pairing) {
    return input_->pair(msg, pairing);
  }
  const std::vector<Ready>& pair(const mb_kinematics_msgs::JointAccelerations& msg);

  // A ~base_odometry message; true when it made R known (the outputs in R may be made now).
  bool add(const nav_msgs::Odometry& msg);

  // A sample taken in at time t (its stamp, or its time of arrival for stamp 0): false (with
  // the warning) when nothing is to be published for it (dropped, or waiting).
  bool add(const Ready& ready, double t);

  using Clock = std::chrono::steady_clock;
  enum class Fill { kDropped, kWaiting, kReady };
  // The state of the sample at t, stamped `stamp`, up to `level`, which it lowers while the
  // estimates lag behind. kDropped (with the warning) if there is none (no base motion, a value
  // check_state refuses). With ~base_odometry, kWaiting while the odometry after t has not come
  // (or an earlier sample waits): the sample, its joints filled, waits in order until release
  // gives it, at most ~base_odometry_wait after `now`.
  Fill fill(double t, const ros::Time& stamp, mbk::Level& level, Clock::time_point now);
  // The oldest waiting sample if it is due at `now` (its odometry came, its wait ended, or more
  // than ~queue_size wait): kReady with its state, stamp and level as fill gives them, kDropped
  // (with the warning) if the odometry gives no base motion for it; kWaiting if none is due.
  Fill release(Clock::time_point now, ros::Time& stamp, mbk::Level& level);
  bool waiting() const { return waiting_count_ > 0; }

  const mbk::JointState<double>& state() const { return state_; }
  // Per body of model() (index k; [0] is R): published with the sample filled (or released).
  const std::vector<char>& published() const { return *published_now_; }
  bool complete() const { return complete_now_; }  // no coordinate missing for that sample

 private:
  // A sample whose joints are filled, waiting for the odometry after its stamp.
  struct Waiting {
    explicit Waiting(const mbk::Model& input) : joints(input) {}
    double t = 0;
    ros::Time stamp;
    mbk::Level level = mbk::Level::kPose;
    Clock::time_point until;
    mbk::JointState<double> joints;  // of input_model_
    std::vector<char> published;
    bool complete = false;
  };
  bool report(const JointStateInput::Update& update);
  bool cover(double t);  // ~missing_coordinates
  void snapshot_published();
  bool fill_base(double t, mbk::Level& level);
  bool check();
  void wait(double t, const ros::Time& stamp, mbk::Level level, Clock::time_point now);

  const NodeParams& params_;
  mbk::Model loaded_;
  // With ~base_odometry the loaded model split in two (BaseOdometryInput::split); without, both
  // are loaded_ itself, not copies (a model of 10,000 bodies takes 4 MB).
  mbk::Model split_input_, split_model_;
  const mbk::Model* input_model_ = &loaded_;    // the joints of joint_states
  const mbk::Model* model_ = &loaded_;          // input_model_, with ~base_odometry after a base
  std::optional<JointStateInput> input_;        // over input_model_
  std::optional<CoordinateCoverage> coverage_;  // over input_model_
  std::vector<char> published_;  // with ~base_odometry: the base, then coverage_'s bodies
  const std::vector<char>* published_now_ = &published_;  // the current sample's
  bool complete_now_ = false;
  // The samples waiting for odometry: a ring (its entries' storage reused), oldest at
  // waiting_first_.
  std::vector<Waiting> waiting_;
  size_t waiting_first_ = 0, waiting_count_ = 0;
  mbk::JointState<double> input_state_, state_;  // input_state_: with ~base_odometry only
  std::unique_ptr<BaseOdometryInput> base_;      // with ~base_odometry
  std::string frame_;
  InputTally tally_;
};

}  // namespace mbk_ros
