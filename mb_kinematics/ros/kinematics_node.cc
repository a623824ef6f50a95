#include "mb_kinematics/ros/kinematics_node.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/derivative_estimator.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/ros/outputs/output_table.h"

namespace mbk_ros {
namespace {

constexpr double kThrottle = 5.0;  // seconds between repeats of one warning

std::string join(const std::vector<std::string>& names, size_t max = 8) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < max; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > max) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

bool finite(const mbk::Data<double>& d, int k, mbk::Level level) {
  bool ok = d.rotation[k].allFinite() && d.origin[k].allFinite() && d.mass_center[k].allFinite();
  if (level != mbk::Level::kPose)
    ok = ok && d.omega[k].allFinite() && d.mass_center_velocity[k].allFinite() &&
         d.origin_velocity[k].allFinite();
  if (level == mbk::Level::kAcceleration)
    ok = ok && d.alpha[k].allFinite() && d.mass_center_acceleration[k].allFinite() &&
         d.origin_acceleration[k].allFinite();
  return ok;
}

// The estimators of the registry that have no latency (the node pairs estimates with the
// newest sample), for messages.
std::string zero_latency_names() {
  std::string out;
  for (const std::string& name : mbk::derivative_estimator_names())
    if (mbk::make_derivative_estimator(name)->latency() == 0) out += name + ", ";
  return out + "savitzky_golay_end_<window>_<order>";
}

// The centered Savitzky-Golay fits and the central difference lag (README, work-precision
// report): the node refuses them.
std::unique_ptr<mbk::DerivativeEstimator> zero_latency_estimator(const std::string& name) {
  std::unique_ptr<mbk::DerivativeEstimator> estimator = mbk::make_derivative_estimator(name);
  if (estimator->latency() > 0)
    throw std::invalid_argument(
        "~acceleration_estimator '" + name + "' estimates " + std::to_string(estimator->latency()) +
        " samples back; the node needs one without latency (" + zero_latency_names() + ")");
  return estimator;
}

// The lower body arrays table has N columns and (max depth + 1) rows: logged whole up to this
// many cells (e.g. 100 bodies of depth up to 99), else a summary (README, "The node").
constexpr long kMaxLoggedTableCells = 10000;

void log_model(const mbk::Model& model, const std::string& frame) {
  int depth = 0;
  for (int k = 1; k <= model.body_count(); ++k) depth = std::max(depth, model.bodies[k].depth);
  const long cells = static_cast<long>(model.body_count()) * (depth + 1);
  std::ostringstream out;
  out << "mb_kinematics: " << model.body_count() << " bodies, " << model.nq
      << " coordinates, max depth " << depth << ", R = '" << frame << "'";
  if (cells <= kMaxLoggedTableCells) {
    std::vector<std::string> names;
    for (int k = 1; k <= model.body_count(); ++k) names.push_back(model.bodies[k].name);
    out << "\n" << mbk::format_lower_body_table(model.lower_body_array(), names);
  } else {
    out << "; the lower body arrays table (" << cells << " cells) is not logged above "
        << kMaxLoggedTableCells << " (mbk tables prints it)";
  }
  ROS_INFO_STREAM(out.str());
  const std::vector<std::string> no_inertia = mbk::bodies_without_inertia(model);
  if (!no_inertia.empty())  // README, "Whole-system quantities"
    ROS_INFO_STREAM(
        "mb_kinematics: body_kinematics' system.angular_momentum is left out "
        "(angular_momentum_known false): no inertia for "
        << no_inertia.size() << " bodies with mass: " << join_names(no_inertia));
}

}  // namespace

KinematicsNode::KinematicsNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : params_(read_node_params(nh, pnh)),
      input_state_(model_),
      state_(model_),
      data_(model_),
      nh_(nh),
      pnh_(pnh) {
  if (!params_.base_odometry.empty())
    base_ = std::make_unique<BaseOdometryInput>(
        *zero_latency_estimator(params_.acceleration_estimator), params_.base_odometry_max_gap);
  start(load_node_model(params_));
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  joint_states_sub_ = nh_.subscribe("joint_states", params_.queue_size,
                                    &KinematicsNode::on_joint_states, this, hints);
  accelerations_sub_ = nh_.subscribe("joint_accelerations", params_.queue_size,
                                     &KinematicsNode::on_joint_accelerations, this, hints);
  if (base_)
    odometry_sub_ = nh_.subscribe(params_.base_odometry, params_.queue_size,
                                  &KinematicsNode::on_odometry, this, hints);
  reload_service_ = pnh_.advertiseService("reload", &KinematicsNode::on_reload, this);
}

// Everything that depends on the model, made anew (at start and by ~reload); the estimators
// start empty. With ~base_odometry the model gets its base (BaseOdometryInput::split).
void KinematicsNode::start(const mbk::Model& loaded) {
  for (auto& o : outputs_)  // services end now, topics once the new ones are advertised
    if (!o->is_service()) retired_.push_back(std::move(o));
  outputs_.clear();
  loaded_ = loaded;
  if (base_)
    BaseOdometryInput::split(loaded_, input_model_, model_);
  else
    input_model_ = model_ = loaded_;
  input_.emplace(input_model_, *zero_latency_estimator(params_.acceleration_estimator),
                 params_.max_sample_gap);
  coverage_.emplace(input_model_, params_.missing_coordinates);
  published_.assign(model_.body_count() + 1, 1);
  input_state_ = mbk::JointState<double>(input_model_);
  state_ = mbk::JointState<double>(model_);
  data_ = mbk::Data<double>(model_);
  last_output_ = -1e300;
  if (base_) base_->reset();
  frame_ = base_                      ? base_->frame()
           : params_.frame_id.empty() ? params_.frame_prefix + model_.frame
                                      : params_.frame_id;
  const OutputSetup setup{nh_, params_, model_, frame_};
  auto diagnostics = std::make_unique<DiagnosticsOutput>(setup, pnh_);
  diagnostics_ = diagnostics.get();
  diagnostics_->watch(*coverage_);
  outputs_.push_back(std::move(diagnostics));
  make_outputs_in_r();
  retired_.clear();
}

// The outputs but /diagnostics, in R: at start, or with ~base_odometry at its first message.
void KinematicsNode::make_outputs_in_r() {
  if (!frame_.empty()) {
    log_model(model_, frame_);
    std::vector<std::unique_ptr<Output>> outputs = make_outputs({nh_, params_, model_, frame_});
    outputs_.insert(outputs_.begin(), std::make_move_iterator(outputs.begin()),
                    std::make_move_iterator(outputs.end()));
  }
  active_.assign(outputs_.size(), 0);
}

// A model that does not load, or whose outputs cannot be made (a ~per_body_topics name it
// lacks), leaves the running one in place (README, "~reload").
bool KinematicsNode::on_reload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  const NodeParams running_params = params_;
  const mbk::Model running = loaded_;
  try {
    read_model_source(nh_, pnh_, params_);
    start(load_node_model(params_));
  } catch (const std::exception& e) {
    params_ = running_params;
    start(running);
    response.success = false;
    response.message = e.what();
    ROS_WARN_STREAM("~reload refused, the running model stays: " << e.what());
    return true;
  }
  response.success = true;
  response.message = "reloaded: " + std::to_string(model_.body_count()) + " bodies, " +
                     std::to_string(model_.nq) + " coordinates";
  ROS_INFO_STREAM("mb_kinematics: " << response.message);
  return true;
}

void KinematicsNode::on_odometry(const nav_msgs::OdometryConstPtr& msg) {
  const ros::Time stamp = msg->header.stamp.isZero() ? ros::Time::now() : msg->header.stamp;
  const std::string error = base_->add(*msg, stamp.toSec());
  if (!error.empty()) {
    warn(InputProblem::kBadOdometry, "base odometry ignored: " + error);
    return;
  }
  if (!frame_.empty()) return;
  frame_ = base_->frame();  // R is known now
  make_outputs_in_r();
}

// The base's coordinates from the odometry at t, the joints' after them; false (with a
// warning) if the odometry has no motion for t.
bool KinematicsNode::add_base(double t, mbk::Level& level) {
  const std::string why = base_->fill(t, model_, input_state_, state_, level);
  if (why.empty()) return true;
  warn(InputProblem::kNoBaseMotion, "joint_states sample dropped: " + why);
  return false;
}

void KinematicsNode::on_joint_states(const sensor_msgs::JointStateConstPtr& msg) {
  diagnostics_->received();
  process(input_->pair(msg, accelerations_sub_.getNumPublishers() > 0));
}

void KinematicsNode::on_joint_accelerations(
    const mb_kinematics_msgs::JointAccelerationsConstPtr& msg) {
  std::string error;
  process(input_->pair(*msg, msg->header.stamp.toSec(), error));
  if (!error.empty())
    warn(InputProblem::kBadAccelerations, "joint_accelerations ignored: " + error);
}

void KinematicsNode::process(const std::vector<JointStateInput::Ready>& ready) {
  for (const JointStateInput::Ready& r : ready) {
    if (r.unpaired)
      diagnostics_->count(InputProblem::kUnpaired,
                          "joint_accelerations missing; accelerations estimated");
    process(*r.sample);
  }
}

// Counts the problem and logs it, at most once per kThrottle seconds per class.
void KinematicsNode::warn(InputProblem problem, const std::string& message) {
  diagnostics_->count(problem, message);
  const auto now = std::chrono::steady_clock::now();
  auto& last = last_warned_[static_cast<size_t>(problem)];
  if (last != std::chrono::steady_clock::time_point() &&
      now - last < std::chrono::duration<double>(kThrottle))
    return;
  last = now;
  ROS_WARN_STREAM(message);
}

// Logs what was wrong with a message; true if the sample may go on.
bool KinematicsNode::report(const JointStateInput::Update& update) {
  if (!update.error.empty()) {
    warn(update.problem, "joint_states sample dropped: " + update.error);
    return false;
  }
  if (!update.unknown.empty())
    warn(InputProblem::kUnknownName,
         "joint_states: ignoring names not in the model: " + join(update.unknown));
  if (!update.reset.empty())
    warn(InputProblem::kStampBackwards, "joint_states: stamp went backwards for " +
                                            join(update.reset) +
                                            "; derivative estimates restarted");
  if (!update.estimator_reset.empty())
    warn(InputProblem::kEstimatorReset,
         "joint_states: estimates of " + join(update.estimator_reset) +
             " went beyond 1e50 or not finite; their estimators restarted from this sample");
  if (update.flipped > 0)
    diagnostics_->count(InputProblem::kEulerSignFlip,
                        "joint_states: Euler parameters negated to stay continuous");
  if (update.used == 0) {
    warn(InputProblem::kNoKnownName, "joint_states: a message without any coordinate of the model");
    return false;
  }
  return true;
}

// The bodies of model_ published with this sample: coverage_'s, after the base (body 1) with
// ~base_odometry (its model_ body k + 1 is input_model_'s body k; base_odometry_input.h).
const std::vector<char>& KinematicsNode::published() {
  const std::vector<char>& covered = coverage_->published();
  if (!base_) return covered;
  for (size_t k = 1; k < covered.size(); ++k) published_[k + 1] = covered[k];
  return published_;
}

// ~missing_coordinates (coordinate_coverage.h): false while waiting; names what is missing
// once, when it changes, and counts each sample published without it.
bool KinematicsNode::cover(double t) {
  const bool changed = coverage_->update(*input_, t);
  if (!coverage_->ready()) {
    warn(InputProblem::kMissingJoints,
         "joint_states: nothing published yet, waiting for joints: " + join(coverage_->never()));
    return false;
  }
  const std::string missing = coverage_->describe();
  if (changed && !missing.empty()) ROS_WARN_STREAM("mb_kinematics: " << missing);
  if (changed && missing.empty()) ROS_INFO_STREAM("mb_kinematics: every joint received");
  if (!coverage_->never().empty() || !coverage_->stale().empty())
    diagnostics_->count(coverage_->mode() == MissingCoordinates::kSkip
                            ? InputProblem::kBodiesLeftOut
                        : coverage_->never().empty() ? InputProblem::kStaleHeld
                                                     : InputProblem::kZeroed,
                        missing);
  return true;
}

mbk::Level KinematicsNode::wanted_level() {
  mbk::Level wanted = mbk::Level::kPose;
  for (size_t i = 0; i < outputs_.size(); ++i) {
    active_[i] = outputs_[i]->active();
    if (active_[i]) wanted = std::max(wanted, outputs_[i]->level());
  }
  return wanted;
}

// forward_kinematics up to `level`, if some listened output reads it; false if not finite.
bool KinematicsNode::compute(mbk::Level level) {
  bool needed = false;
  for (size_t i = 0; i < outputs_.size(); ++i)
    needed = needed || (active_[i] && outputs_[i]->uses_data() && outputs_[i]->level() <= level);
  if (!needed) return true;
  mbk::forward_kinematics(model_, state_, data_, level);
  for (int k = 1; k <= model_.body_count(); ++k) {
    if (finite(data_, k, level)) continue;
    warn(InputProblem::kKinematicsNotFinite,
         "kinematics of body '" + model_.bodies[k].name + "' not finite; dropped");
    return false;
  }
  return true;
}

// ~publish_frequency: true for a sample less than a period (by stamp) after the last one that
// went out; a stamp going backwards starts again.
bool KinematicsNode::decimated(double t) {
  if (params_.publish_frequency <= 0) return false;
  const double period = 1.0 / params_.publish_frequency;
  if (t >= last_output_ && t - last_output_ < period * (1 - 1e-9)) return true;
  last_output_ = t;
  return false;
}

// The listened outputs that read the data (or not) and that the sample's level satisfies.
void KinematicsNode::publish(const ros::Time& stamp, const Sample& sample, bool uses_data) {
  for (size_t i = 0; i < outputs_.size(); ++i)
    if (active_[i] && outputs_[i]->uses_data() == uses_data && outputs_[i]->level() <= sample.level)
      outputs_[i]->publish(stamp, sample);
}

void KinematicsNode::process(const sensor_msgs::JointState& msg) {
  const auto start = std::chrono::steady_clock::now();
  const ros::Time stamp = msg.header.stamp.isZero() ? ros::Time::now() : msg.header.stamp;
  if (msg.header.stamp.isZero())
    diagnostics_->count(InputProblem::kZeroStamp, "joint_states: stamp 0, time of arrival used");
  if (!report(input_->add(msg, stamp.toSec()))) return;
  if (base_ && frame_.empty()) {
    warn(InputProblem::kNoOdometry,
         "nothing published yet, waiting for base odometry on " + odometry_sub_.getTopic());
    return;
  }
  if (!cover(stamp.toSec())) return;
  if (decimated(stamp.toSec())) return;  // the estimators have taken the sample in
  const mbk::Level wanted = wanted_level();
  mbk::Level level = input_->fill(wanted, input_->paired(stamp.toSec()),
                                  base_ ? input_state_ : state_, &coverage_->from_input());
  if (base_ && !add_base(stamp.toSec(), level)) return;
  const std::string bad = mbk::check_state(model_, state_);  // NaN/Inf, zero quaternions, ...
  if (!bad.empty()) {  // estimates of given velocities, mimics: the input checked the rest
    warn(bad.find("not finite") != std::string::npos ? InputProblem::kNonFinite
                                                     : InputProblem::kTooLarge,
         bad + "; sample dropped");
    return;
  }
  const Sample sample{model_, state_, data_, level, published(), coverage_->complete()};
  publish(stamp, sample, false);  // from the joint state alone (tf) first
  if (!compute(level)) return;
  publish(stamp, sample, true);
  if (level < wanted)
    ROS_INFO_STREAM_THROTTLE(kThrottle,
                             "mb_kinematics: estimating derivatives, "
                             "velocities/accelerations follow after 3 samples");
  diagnostics_->published(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace mbk_ros
