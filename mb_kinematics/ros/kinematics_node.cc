#include "mb_kinematics/ros/kinematics_node.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <mutex>
#include <sstream>
#include <string>

#include "mb_kinematics/core/finite_kinematics.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/ros/heap_trim.h"
#include "mb_kinematics/ros/outputs/output_table.h"

namespace mbk_ros {
namespace {

constexpr double kNoticeThrottle = 5.0;  // seconds between repeats of the estimating notice
constexpr double kPairingPeriod = 0.05;  // seconds between looks for joint_accelerations publishers

// The lower body arrays table has N columns and (max depth + 1) rows: logged whole up to this
// many cells (e.g. 100 bodies of depth up to 99), else a summary (doc/node.md).
constexpr long kMaxLoggedTableCells = 10000;

// `tf`: whether ~outputs has tf (publish_tf:=false takes it out), said in the start-up line.
void log_model(const mbk::Model& model, const std::string& frame, bool tf) {
  for (const std::string& warning : model.warnings)
    ROS_WARN_STREAM("mb_kinematics: " << mbk::printable(warning));
  int depth = 0;
  for (int k = 1; k <= model.body_count(); ++k) depth = std::max(depth, model.bodies[k].depth);
  const long cells = static_cast<long>(model.body_count()) * (depth + 1);
  const std::vector<std::string> no_inertia = mbk::bodies_without_inertia(model);
  ROS_INFO_STREAM("mb_kinematics: "
                  << model.body_count() << " bodies, " << model.nq << " coordinates, max depth "
                  << depth << ", R = '" << frame
                  << "'; kinematics of every body and the system, angular "
                  << (no_inertia.empty() ? "momentum included" : "momentum left out (inertias)")
                  << (tf ? "; frames on /tf"
                         : "; no /tf (~outputs without tf: publish_tf:=false)"));
  if (cells <= kMaxLoggedTableCells) {
    std::vector<std::string> names;
    for (int k = 1; k <= model.body_count(); ++k) names.push_back(model.bodies[k].name);
    ROS_DEBUG_STREAM("mb_kinematics: lower body arrays\n"
                     << mbk::format_lower_body_table(model.lower_body_array(), names));
  } else {
    ROS_DEBUG_STREAM("mb_kinematics: the lower body arrays table ("
                     << cells << " cells) is not "
                     << "logged above " << kMaxLoggedTableCells << " (mbk tables prints it)");
  }
  if (!no_inertia.empty())  // doc/node.md, system
    ROS_DEBUG_STREAM(
        "mb_kinematics: body_kinematics' system.angular_momentum is left out "
        "(angular_momentum_known false): no inertia for "
        << no_inertia.size() << " bodies with mass: " << join_names(no_inertia));
}

}  // namespace

KinematicsNode::KinematicsNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : params_(read_node_params(nh, pnh)),
      nh_(nh),
      pnh_(pnh),
      input_(params_, params_.base_odometry.empty() ? "" : nh.resolveName(params_.base_odometry)),
      data_(input_.model()) {
  const mbk::ModelFile loaded = load_node_model(params_);
  start(loaded.model, loaded.missing_segments);
  joint_states_sub_ = subscribe("joint_states", &KinematicsNode::on_joint_states);
  accelerations_sub_ = subscribe("joint_accelerations", &KinematicsNode::on_joint_accelerations);
  pairing_timer_ = nh_.createWallTimer(
      ros::WallDuration(kPairingPeriod),
      [this](const ros::WallTimerEvent&) { pairing_ = accelerations_sub_.getNumPublishers() > 0; });
  if (!params_.base_odometry.empty())
    odometry_sub_ = subscribe(params_.base_odometry, &KinematicsNode::on_odometry);
  if (!params_.base_odometry.empty() && params_.base_odometry_wait > 0)
    wait_timer_ = nh_.createSteadyTimer(ros::WallDuration(params_.base_odometry_wait / 4),
                                        [this](const ros::SteadyTimerEvent&) {
                                          std::lock_guard<std::mutex> lock(queue_.mutex());
                                          if (input_.waiting())
                                            release_waiting(NodeInput::Clock::now());
                                        });
  reload_service_ = pnh_.advertiseService("reload", &KinematicsNode::on_reload, this);
}

template <typename M>
ros::Subscriber KinematicsNode::subscribe(
    const std::string& topic, void (KinematicsNode::*callback)(const boost::shared_ptr<const M>&)) {
  ros::SubscribeOptions options;
  options.init<M>(
      topic, params_.queue_size,
      [this, callback](const boost::shared_ptr<const M>& msg) { (this->*callback)(msg); });
  options.transport_hints = ros::TransportHints().tcpNoDelay();
  options.callback_queue = &queue_;
  return nh_.subscribe(options);
}

// Everything that depends on the model, made anew (at start and by ~reload); the outputs that
// need no R (/diagnostics) first.
void KinematicsNode::start(const mbk::Model& loaded,
                           const std::vector<std::string>& missing_segments) {
  outputs_.clear();
  input_.load(loaded);
  missing_segments_ = missing_segments;
  data_ = mbk::Data<double>(input_.model());
  rate_ = PublishRate(params_.publish_frequency);
  outputs_ = make_outputs(setup(), false);
  make_outputs_in_r();
  release_freed_heap();  // what reading the model freed (its XML)
}

OutputSetup KinematicsNode::setup() {
  return {nh_,
          pnh_,
          params_,
          input_.model(),
          missing_segments_,
          input_.frame(),
          input_.tally(),
          input_.coverage(),
          queue_.mutex()};
}

// The outputs in R, before those made at start: at start, or with ~base_odometry at its first
// message.
void KinematicsNode::make_outputs_in_r() {
  if (!input_.frame().empty()) {
    log_model(input_.model(), input_.frame(), params_.tf);
    Outputs outputs = make_outputs(setup(), true);
    outputs_.insert(outputs_.begin(), std::make_move_iterator(outputs.begin()),
                    std::make_move_iterator(outputs.end()));
  }
  active_.assign(outputs_.size(), 0);
}

// A model that does not load, or whose outputs cannot be made (a ~per_body_topics name it
// lacks), leaves the running one in place (doc/node.md, "~reload"). The services end first, the
// topics once the new ones are advertised (`retired`), so that subscribers stay connected.
bool KinematicsNode::on_reload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  std::lock_guard<std::mutex> lock(queue_.mutex());
  for (auto& o : outputs_) o->cancel_calls();  // ending a service waits for its calls
  const NodeParams running_params = params_;
  const mbk::Model running = input_.loaded();
  const std::vector<std::string> running_missing = missing_segments_;
  Outputs retired;
  for (auto& o : outputs_)
    if (!o->is_service()) retired.push_back(std::move(o));
  outputs_.clear();
  try {
    read_model_source(nh_, pnh_, params_);
    const mbk::ModelFile loaded = load_node_model(params_);
    start(loaded.model, loaded.missing_segments);
  } catch (const std::exception& e) {
    params_ = running_params;
    start(running, running_missing);
    response.success = false;
    response.message = e.what();
    ROS_WARN_STREAM("~reload refused, the running model stays: " << mbk::printable(e.what()));
    return true;
  }
  response.success = true;
  response.message = "reloaded: " + std::to_string(input_.model().body_count()) + " bodies, " +
                     std::to_string(input_.model().nq) + " coordinates";
  ROS_INFO_STREAM("mb_kinematics: " << response.message);
  return true;
}

void KinematicsNode::on_odometry(const nav_msgs::OdometryConstPtr& msg) {
  if (input_.add(*msg)) make_outputs_in_r();  // R is known now
  release_waiting(NodeInput::Clock::now());   // the samples this message completes
}

void KinematicsNode::on_joint_states(const sensor_msgs::JointStateConstPtr& msg) {
  input_.tally().received();
  process(input_.pair(msg, pairing_));
}

void KinematicsNode::on_joint_accelerations(
    const mb_kinematics_msgs::JointAccelerationsConstPtr& msg) {
  pairing_ = true;
  process(input_.pair(*msg));
}

void KinematicsNode::process(const std::vector<NodeInput::Ready>& ready) {
  for (const NodeInput::Ready& r : ready) process(r);
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
  const mbk::Model& model = input_.model();
  mbk::forward_kinematics(model, input_.state(), data_, level);
  if (mbk::finite_kinematics(data_, level)) return true;  // else the first body not finite is named
  for (int k = 1; k <= model.body_count(); ++k) {
    if (mbk::finite_kinematics(data_, k, level)) continue;
    input_.tally().warn(InputProblem::kKinematicsNotFinite,
                        "kinematics of body '" + model.bodies[k].name + "' not finite; dropped");
    return false;
  }
  return true;
}

// The listened outputs that read the data (or not) and that the sample's level satisfies.
void KinematicsNode::publish(const ros::Time& stamp, const Sample& sample, bool uses_data) {
  for (size_t i = 0; i < outputs_.size(); ++i)
    if (active_[i] && outputs_[i]->uses_data() == uses_data && outputs_[i]->level() <= sample.level)
      outputs_[i]->publish(stamp, sample);
}

void KinematicsNode::process(const NodeInput::Ready& ready) {
  const auto start = NodeInput::Clock::now();
  release_waiting(start);  // the samples before this one first
  const ros::Time& given = ready.sample->header.stamp;
  const ros::Time stamp = given.isZero() ? ros::Time::now() : given;
  if (!input_.add(ready, stamp.toSec())) return;
  if (rate_.skip(stamp.toSec())) return;  // the estimators have taken the sample in
  const mbk::Level wanted = wanted_level();
  mbk::Level level = wanted;
  const NodeInput::Fill fill = input_.fill(stamp.toSec(), stamp, level, start);
  if (fill == NodeInput::Fill::kReady) emit(stamp, level, wanted, start);
  if (fill == NodeInput::Fill::kWaiting) release_waiting(start);  // more than ~queue_size wait
}

void KinematicsNode::release_waiting(NodeInput::Clock::time_point now) {
  ros::Time stamp;
  mbk::Level level = mbk::Level::kPose;
  for (NodeInput::Fill fill;
       (fill = input_.release(now, stamp, level)) != NodeInput::Fill::kWaiting;)
    if (fill == NodeInput::Fill::kReady) {
      const mbk::Level wanted = wanted_level();
      emit(stamp, std::min(level, wanted), wanted, NodeInput::Clock::now());
    }
}

void KinematicsNode::emit(const ros::Time& stamp, mbk::Level level, mbk::Level wanted,
                          NodeInput::Clock::time_point start) {
  const Sample sample{input_.model(), input_.state(),     data_,
                      level,          input_.published(), input_.complete()};
  publish(stamp, sample, false);  // from the joint state alone (tf) first
  if (!compute(level)) return;
  publish(stamp, sample, true);
  if (level < wanted)
    ROS_INFO_STREAM_THROTTLE(kNoticeThrottle,
                             "mb_kinematics: estimating derivatives, "
                             "velocities/accelerations follow after 3 samples");
  input_.tally().published(std::chrono::duration<double>(NodeInput::Clock::now() - start).count());
}

}  // namespace mbk_ros
