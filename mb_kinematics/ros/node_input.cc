#include "mb_kinematics/ros/node_input.h"

#include <ros/console.h>
#include <ros/time.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/messages/frames.h"

namespace mbk_ros {
namespace {

// The estimators of the registry that have no latency (the node pairs estimates with the
// newest sample), for messages.
std::string zero_latency_names() {
  std::string out;
  for (const std::string& name : mbk::derivative_estimator_names())
    if (mbk::make_derivative_estimator(name)->latency() == 0) out += name + ", ";
  return out + "savitzky_golay_end_<window>_<order>";
}

// The centered Savitzky-Golay fits and the central difference lag (doc/error_vs_runtime.md
// report): the node refuses them.
std::unique_ptr<mbk::DerivativeEstimator> zero_latency_estimator(const std::string& name) {
  std::unique_ptr<mbk::DerivativeEstimator> estimator = mbk::make_derivative_estimator(name);
  if (estimator->latency() > 0)
    throw std::invalid_argument(
        "~acceleration_estimator '" + name + "' estimates " + std::to_string(estimator->latency()) +
        " samples back; the node needs one without latency (" + zero_latency_names() + ")");
  return estimator;
}

}  // namespace

NodeInput::NodeInput(const NodeParams& params, const std::string& odometry_topic)
    : params_(params), input_state_(loaded_), state_(loaded_) {
  if (!params_.base_odometry.empty())
    base_ =
        std::make_unique<BaseOdometryInput>(*zero_latency_estimator(params_.acceleration_estimator),
                                            params_.base_odometry_max_gap, odometry_topic);
}

void NodeInput::load(const mbk::Model& loaded) {
  loaded_ = loaded;
  input_model_ = model_ = &loaded_;
  if (base_) {
    BaseOdometryInput::split(loaded_, split_input_, split_model_);
    input_model_ = &split_input_;
    model_ = &split_model_;
  }
  input_.emplace(*input_model_, *zero_latency_estimator(params_.acceleration_estimator),
                 params_.max_sample_gap);
  coverage_.emplace(*input_model_, params_.missing_coordinates);
  published_.assign(model_->body_count() + 1, 1);
  input_state_ = mbk::JointState<double>(*input_model_);
  state_ = mbk::JointState<double>(*model_);
  if (base_) base_->reset();
  published_now_ = &published_;
  waiting_.clear();
  waiting_first_ = waiting_count_ = 0;
  frame_ = base_                      ? base_->frame()
           : params_.frame_id.empty() ? mbk_messages::model_frame(*model_, params_.frame_prefix)
                                      : params_.frame_id;
  tally_.restart();
}

const std::vector<NodeInput::Ready>& NodeInput::pair(
    const mb_kinematics_msgs::JointAccelerations& msg) {
  std::string error;
  const std::vector<Ready>& ready = input_->pair(msg, msg.header.stamp.toSec(), error);
  if (!error.empty())
    tally_.warn(InputProblem::kBadAccelerations, "joint_accelerations ignored: " + error);
  return ready;
}

bool NodeInput::add(const nav_msgs::Odometry& msg) {
  const ros::Time stamp = msg.header.stamp.isZero() ? ros::Time::now() : msg.header.stamp;
  const std::string error = base_->add(msg, stamp.toSec());
  if (!error.empty()) {
    tally_.warn(InputProblem::kBadOdometry, "base odometry ignored: " + error);
    return false;
  }
  if (!frame_.empty()) return false;
  frame_ = base_->frame();
  return true;
}

bool NodeInput::add(const Ready& ready, double t) {
  if (ready.unpaired)
    tally_.count(InputProblem::kUnpaired, "joint_accelerations missing; accelerations estimated");
  if (ready.sample->header.stamp.isZero())
    tally_.count(InputProblem::kZeroStamp, "joint_states: stamp 0, time of arrival used");
  if (!report(input_->add(*ready.sample, t))) return false;
  if (base_ && frame_.empty()) {
    tally_.warn(InputProblem::kNoOdometry,
                "nothing published yet, waiting for base odometry on " + base_->topic());
    return false;
  }
  return cover(t);
}

// Logs what was wrong with a message; true if the sample may go on.
bool NodeInput::report(const JointStateInput::Update& update) {
  if (!update.error.empty()) {
    tally_.warn(update.problem, "joint_states sample dropped: " + update.error);
    return false;
  }
  if (!update.unknown.empty())
    tally_.warn(InputProblem::kUnknownName,
                "joint_states: ignoring names not in the model: " + join_names(update.unknown));
  if (!update.reset.empty())
    tally_.warn(InputProblem::kStampBackwards, "joint_states: stamp went backwards for " +
                                                   join_names(update.reset) +
                                                   "; derivative estimates restarted");
  if (!update.estimator_reset.empty())
    tally_.warn(InputProblem::kEstimatorReset,
                "joint_states: estimates of " + join_names(update.estimator_reset) +
                    " went beyond 1e50 or not finite; their estimators restarted from this sample");
  if (update.flipped > 0)
    tally_.count(InputProblem::kEulerSignFlip,
                 "joint_states: Euler parameters negated to stay continuous");
  if (update.used == 0) {
    tally_.warn(InputProblem::kNoKnownName,
                "joint_states: a message without any coordinate of the model");
    return false;
  }
  return true;
}

// ~missing_coordinates (coordinate_coverage.h): false while waiting; names what is missing
// once, when it changes, and counts each sample published without it.
bool NodeInput::cover(double t) {
  const bool changed = coverage_->update(*input_, t);
  if (!coverage_->ready()) {
    tally_.warn(InputProblem::kMissingJoints,
                "joint_states: nothing published yet, waiting for joints: " +
                    join_names(coverage_->never()));
    return false;
  }
  const std::string missing = coverage_->describe();
  if (changed && !missing.empty()) ROS_WARN_STREAM("mb_kinematics: " << mbk::printable(missing));
  if (changed && missing.empty()) ROS_INFO_STREAM("mb_kinematics: every joint received");
  if (!coverage_->never().empty() || !coverage_->stale().empty())
    tally_.count(coverage_->mode() == MissingCoordinates::kSkip ? InputProblem::kBodiesLeftOut
                 : coverage_->never().empty()                   ? InputProblem::kStaleHeld
                                                                : InputProblem::kZeroed,
                 missing);
  return true;
}

NodeInput::Fill NodeInput::fill(double t, const ros::Time& stamp, mbk::Level& level,
                                Clock::time_point now) {
  bool checked = false;  // check_state's verdict known: JointStateInput::fill
  level = input_->fill(level, input_->paired(t), base_ ? input_state_ : state_,
                       &coverage_->from_input(), &checked);
  snapshot_published();
  if (!base_) return checked || check() ? Fill::kReady : Fill::kDropped;
  if (params_.base_odometry_wait > 0 && (waiting_count_ > 0 || !base_->covers(t))) {
    wait(t, stamp, level, now);  // in order behind the samples waiting already
    return Fill::kWaiting;
  }
  return fill_base(t, level) ? Fill::kReady : Fill::kDropped;
}

// Keeps the sample just filled at the end of the ring, grown by one when full.
void NodeInput::wait(double t, const ros::Time& stamp, mbk::Level level, Clock::time_point now) {
  if (waiting_count_ == waiting_.size()) {
    std::rotate(waiting_.begin(), waiting_.begin() + waiting_first_, waiting_.end());
    waiting_first_ = 0;
    waiting_.emplace_back(*input_model_);
  }
  Waiting& w = waiting_[(waiting_first_ + waiting_count_++) % waiting_.size()];
  w.t = t;
  w.stamp = stamp;
  w.level = level;
  w.until = now + std::chrono::duration_cast<Clock::duration>(
                      std::chrono::duration<double>(params_.base_odometry_wait));
  w.joints = input_state_;  // storage reused
  w.published = *published_now_;
  w.complete = complete_now_;
}

NodeInput::Fill NodeInput::release(Clock::time_point now, ros::Time& stamp, mbk::Level& level) {
  if (waiting_count_ == 0) return Fill::kWaiting;
  Waiting& w = waiting_[waiting_first_];
  const bool overflow = waiting_count_ > static_cast<size_t>(params_.queue_size);
  if (!base_->covers(w.t) && now < w.until && !overflow) return Fill::kWaiting;
  waiting_first_ = (waiting_first_ + 1) % waiting_.size();
  --waiting_count_;
  std::swap(input_state_, w.joints);
  std::swap(published_, w.published);
  published_now_ = &published_;
  complete_now_ = w.complete;
  stamp = w.stamp;
  level = w.level;
  return fill_base(w.t, level) ? Fill::kReady : Fill::kDropped;
}

// The base's coordinates from the odometry at t (interpolated; held or extrapolated, counted),
// the joints' after them.
bool NodeInput::fill_base(double t, mbk::Level& level) {
  using Fit = mbk::BaseOdometryBuffer::Fit;
  Fit fit = Fit::kEmpty;
  const std::string why =
      base_->fill(t, *model_, input_state_, state_, level, params_.base_odometry_extrapolate, fit);
  if (!why.empty()) {
    tally_.warn(InputProblem::kNoBaseMotion, "joint_states sample dropped: " + why);
    return false;
  }
  if (fit == Fit::kHeld || fit == Fit::kExtrapolated)
    tally_.warn(fit == Fit::kHeld ? InputProblem::kBaseHeld : InputProblem::kBaseExtrapolated,
                base_->beyond(t, fit == Fit::kExtrapolated));
  return check();
}

// The state against check_state (NaN/Inf, zero quaternions, ...): estimates of given
// velocities, mimics; the input checked the rest.
bool NodeInput::check() {
  const std::string bad = mbk::check_state(*model_, state_);
  if (bad.empty()) return true;
  tally_.warn(bad.find("not finite") != std::string::npos ? InputProblem::kNonFinite
                                                          : InputProblem::kTooLarge,
              bad + "; sample dropped");
  return false;
}

// The current sample's published bodies: coverage_'s, after the base (body 1) with
// ~base_odometry (its model_ body k + 1 is input_model_'s body k; base_odometry_input.h).
void NodeInput::snapshot_published() {
  complete_now_ = coverage_->complete();
  const std::vector<char>& covered = coverage_->published();
  if (!base_) {
    published_now_ = &covered;
    return;
  }
  for (size_t k = 1; k < covered.size(); ++k) published_[k + 1] = covered[k];
  published_now_ = &published_;
}

}  // namespace mbk_ros
