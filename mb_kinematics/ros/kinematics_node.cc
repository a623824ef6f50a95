#include "mb_kinematics/ros/kinematics_node.h"

#include <geometry_msgs/AccelStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <mb_kinematics_msgs/LowerBodyArray.h>

#include <cctype>
#include <stdexcept>

#include "mb_kinematics/core/derivative_estimator.h"
#include "mb_kinematics/core/error_indicators.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/io/urdf_model.h"

namespace mbk_ros {
namespace {

constexpr double kThrottle = 5.0;  // seconds between repeats of one warning
constexpr size_t kKeptAccelerations = 16;

std::string join(const std::vector<std::string>& names, size_t max = 8) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < max; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > max) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

// A graph-name-safe version of a body name for per-body topics.
std::string topic_name(const std::string& body) {
  std::string out = body;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out[0]))) out = "b_" + out;
  return out;
}

template <typename T>
void set_vector(const mbk::Vec3<double>& v, T& out) {
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
}

void set_transform(const mbk::Body& body, const mbk::JointMotion<double>& m,
                   geometry_msgs::Transform& out) {
  set_vector(body.joint.offset + m.translation, out.translation);  // q_k + s_k, in Bj
  const Eigen::Quaterniond q(m.rotation);                          // SJK
  out.rotation.x = q.x();
  out.rotation.y = q.y();
  out.rotation.z = q.z();
  out.rotation.w = q.w();
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

}  // namespace

mbk::Model load_node_model(const NodeParams& p) {
  mbk::Model model;
  if (!p.lower_body_array.empty()) {
    model = mbk::make_bare_model(p.lower_body_array, mbk::joint_type_from_string(p.joint_type));
  } else if (!p.model.empty()) {
    model = mbk::load_model_file(p.model);
  } else if (!p.robot_description.empty()) {
    model = mbk::load_urdf_string(p.robot_description, "robot_description");
  } else {
    throw std::invalid_argument(
        "no model: set the robot_description parameter (URDF), ~model (a .urdf or .yaml "
        "path) or ~lower_body_array");
  }
  if (model.speeds != mbk::SpeedKind::kCoordinateDerivatives) {  // the node's speeds: q'
    model.speeds = mbk::SpeedKind::kCoordinateDerivatives;
    mbk::finalize_model(model);
  }
  return model;
}

namespace {

// The node pairs estimates with the newest sample, so it takes only estimators without latency
// (the centered Savitzky-Golay fits and the central difference lag: see the README's
// work-precision report).
std::unique_ptr<mbk::DerivativeEstimator> zero_latency_estimator(const std::string& name) {
  std::unique_ptr<mbk::DerivativeEstimator> estimator = mbk::make_derivative_estimator(name);
  if (estimator->latency() > 0)
    throw std::invalid_argument("~acceleration_estimator '" + name + "' estimates " +
                                std::to_string(estimator->latency()) +
                                " samples back; the node needs one without latency (kalman, "
                                "kalman_smooth, backward_difference, savitzky_golay_end_<w>_<o>)");
  return estimator;
}

}  // namespace

KinematicsNode::KinematicsNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : params_(read_node_params(nh, pnh)),
      model_(load_node_model(params_)),
      frame_(params_.frame_id.empty() ? model_.frame : params_.frame_id),
      input_(model_, *zero_latency_estimator(params_.acceleration_estimator),
             params_.max_sample_gap),
      state_(model_),
      previous_state_(model_),
      data_(model_),
      nh_(nh),
      pnh_(pnh),
      updater_(nh, pnh) {
  std::vector<std::string> names;
  for (int k = 1; k <= model_.body_count(); ++k) names.push_back(model_.bodies[k].name);
  ROS_INFO_STREAM("mb_kinematics: "
                  << model_.body_count() << " bodies, " << model_.nq << " coordinates, R = '"
                  << frame_ << "'\n"
                  << mbk::format_lower_body_table(model_.lower_body_array(), names));
  for (int k = 1; k <= model_.body_count(); ++k)
    if (mbk::coordinate_count(model_.bodies[k].joint.type) > 0) moving_.push_back(k);
  transforms_.resize(moving_.size());
  last_tf_stamp_.resize(moving_.size());
  for (size_t i = 0; i < moving_.size(); ++i) {
    const mbk::Body& body = model_.bodies[moving_[i]];
    transforms_[i].header.frame_id = body.lower ? model_.bodies[body.lower].name : frame_;
    transforms_[i].child_frame_id = body.name;
  }
  advertise();
  if (params_.tf) publish_static_tf();
  updater_.setHardwareID("none");
  updater_.add("Joint state input", this, &KinematicsNode::diagnose);
  window_start_ = std::chrono::steady_clock::now();
  diagnostics_timer_ =
      nh_.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  joint_states_sub_ = nh_.subscribe("joint_states", 50, &KinematicsNode::on_joint_states, this);
  accelerations_sub_ =
      nh_.subscribe("joint_accelerations", 50, &KinematicsNode::on_joint_accelerations, this);
}

void KinematicsNode::advertise() {
  mb_kinematics_msgs::LowerBodyArray topology;
  topology.header.stamp = ros::Time::now();
  topology.header.frame_id = frame_;
  for (int k = 1; k <= model_.body_count(); ++k) {
    topology.names.push_back(model_.bodies[k].name);
    topology.lower.push_back(model_.bodies[k].lower);
  }
  lower_body_pub_ = nh_.advertise<mb_kinematics_msgs::LowerBodyArray>("lower_body_array", 1, true);
  lower_body_pub_.publish(topology);
  if (params_.body_kinematics)
    kinematics_pub_ = nh_.advertise<mb_kinematics_msgs::BodyKinematicsArray>("body_kinematics", 10);
  if (params_.publish_markers)
    markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("body_kinematics/markers", 10);
  kinematics_msg_.header.frame_id = frame_;
  kinematics_msg_.bodies.resize(model_.body_count());
  for (int k = 1; k <= model_.body_count(); ++k) {
    auto& b = kinematics_msg_.bodies[k - 1];
    b.name = model_.bodies[k].name;
    b.index = k;
    b.lower_body = model_.bodies[k].lower;
  }
  if (!params_.per_body_topics) return;
  twist_pubs_.resize(model_.body_count() + 1);
  accel_pubs_.resize(model_.body_count() + 1);
  for (int k = 1; k <= model_.body_count(); ++k) {
    const std::string base = "body/" + topic_name(model_.bodies[k].name);
    if (params_.twist)
      twist_pubs_[k] = nh_.advertise<geometry_msgs::TwistStamped>(base + "/twist", 10);
    if (params_.accel)
      accel_pubs_[k] = nh_.advertise<geometry_msgs::AccelStamped>(base + "/accel", 10);
  }
}

// Fixed joints: SJK and q_k never change, so /tf_static once (doc/method.md 8).
void KinematicsNode::publish_static_tf() {
  std::vector<geometry_msgs::TransformStamped> fixed;
  mbk::JointMotion<double> m;
  for (int k = 1; k <= model_.body_count(); ++k) {
    const mbk::Body& body = model_.bodies[k];
    if (mbk::coordinate_count(body.joint.type) > 0) continue;
    mbk::joint_motion<double>(body.joint, model_.speeds, nullptr, nullptr, m);
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = body.lower ? model_.bodies[body.lower].name : frame_;
    t.child_frame_id = body.name;
    set_transform(body, m, t.transform);
    fixed.push_back(t);
  }
  if (!fixed.empty()) static_broadcaster_.sendTransform(fixed);
}

// What the subscribed outputs need: no subscriber, no velocity or acceleration work.
mbk::Level KinematicsNode::wanted_level() const {
  bool velocity = false;
  bool acceleration = (kinematics_pub_ && kinematics_pub_.getNumSubscribers() > 0) ||
                      (markers_pub_ && markers_pub_.getNumSubscribers() > 0);
  for (size_t k = 1; k < twist_pubs_.size() && !acceleration; ++k) {
    velocity = velocity || (twist_pubs_[k] && twist_pubs_[k].getNumSubscribers() > 0);
    acceleration = accel_pubs_[k] && accel_pubs_[k].getNumSubscribers() > 0;
  }
  if (acceleration) return mbk::Level::kAcceleration;
  return velocity ? mbk::Level::kVelocity : mbk::Level::kPose;
}

const AccelerationSample* KinematicsNode::accelerations_at(double t) const {
  for (const AccelerationSample& a : accelerations_)
    if (a.stamp == t) return &a;
  return nullptr;
}

void KinematicsNode::on_joint_states(const sensor_msgs::JointStateConstPtr& msg) {
  ++total_.received;
  ++window_.received;
  if (pending_) {  // its accelerations did not come in time: estimate them
    const sensor_msgs::JointStateConstPtr previous = pending_;
    pending_.reset();
    process(*previous);
  }
  const bool pairing = accelerations_sub_.getNumPublishers() > 0;
  if (pairing && !accelerations_at(msg->header.stamp.toSec())) {
    pending_ = msg;  // wait for joint_accelerations of the same stamp (or the next sample)
    return;
  }
  process(*msg);
}

void KinematicsNode::on_joint_accelerations(
    const mb_kinematics_msgs::JointAccelerationsConstPtr& msg) {
  AccelerationSample sample;
  const std::string error = input_.convert(*msg, msg->header.stamp.toSec(), sample);
  if (!error.empty()) {
    last_problem_ = "joint_accelerations ignored: " + error;
    ROS_WARN_STREAM_THROTTLE(kThrottle, last_problem_);
    return;
  }
  if (!accelerations_.empty() && sample.stamp < accelerations_.back().stamp)
    accelerations_.clear();  // stamps went backwards (a bag looping)
  accelerations_.push_back(std::move(sample));
  if (accelerations_.size() > kKeptAccelerations) accelerations_.pop_front();
  if (pending_ && pending_->header.stamp == msg->header.stamp) {
    const sensor_msgs::JointStateConstPtr sample_msg = pending_;
    pending_.reset();
    process(*sample_msg);
  }
}

// Logs what was wrong with a message; true if the sample may go on.
bool KinematicsNode::report(const JointStateInput::Update& update) {
  if (!update.error.empty()) {
    ++total_.dropped;
    ++window_.dropped;
    last_problem_ = "joint_states sample dropped: " + update.error;
    ROS_WARN_STREAM_THROTTLE(kThrottle, last_problem_);
    return false;
  }
  if (!update.unknown.empty())
    ROS_WARN_STREAM_THROTTLE(
        kThrottle, "joint_states: ignoring names not in the model: " << join(update.unknown));
  if (!update.reset.empty())
    ROS_WARN_STREAM_THROTTLE(kThrottle, "joint_states: stamp went backwards for "
                                            << join(update.reset)
                                            << "; derivative estimates restarted");
  if (update.used == 0) return false;
  const std::vector<std::string> missing = input_.missing();
  if (!missing.empty()) {
    ++total_.incomplete;
    ++window_.incomplete;
    last_problem_ = "waiting for joints: " + join(missing);
    ROS_WARN_STREAM_THROTTLE(kThrottle, "joint_states: nothing published yet, " << last_problem_);
    return false;
  }
  return true;
}

void KinematicsNode::process(const sensor_msgs::JointState& msg) {
  const auto start = std::chrono::steady_clock::now();
  const ros::Time stamp = msg.header.stamp.isZero() ? ros::Time::now() : msg.header.stamp;
  if (!report(input_.add(msg, stamp.toSec()))) return;
  const mbk::Level wanted = wanted_level();
  const mbk::Level level = input_.fill(wanted, accelerations_at(stamp.toSec()), state_);
  const std::string bad = mbk::check_state(model_, state_);  // NaN/Inf, zero quaternions, ...
  if (!bad.empty()) {
    last_problem_ = bad + "; sample dropped";
    ROS_WARN_STREAM_THROTTLE(kThrottle, last_problem_);
    ++total_.dropped;
    ++window_.dropped;
    return;
  }
  if (level == mbk::Level::kAcceleration && previous_stamp_ >= 0 &&
      stamp.toSec() > previous_stamp_) {  // no prediction across a backwards jump
    const double residual =
        mbk::prediction_residual(previous_state_, state_, stamp.toSec() - previous_stamp_);
    for (Counters* c : {&total_, &window_}) c->max_residual = std::max(c->max_residual, residual);
  }
  previous_state_ = state_;
  previous_stamp_ = level == mbk::Level::kAcceleration ? stamp.toSec() : -1;
  if (params_.tf) publish_tf(stamp);
  if (level != mbk::Level::kPose && !publish_kinematics(stamp, level)) return;
  if (level < wanted)
    ROS_INFO_STREAM_THROTTLE(kThrottle,
                             "mb_kinematics: estimating derivatives, "
                             "velocities/accelerations follow after 3 samples");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (Counters* c : {&total_, &window_}) {
    ++c->published;
    c->update_seconds += seconds;
    c->max_update_seconds = std::max(c->max_update_seconds, seconds);
  }
}

// The relative transform of each moving joint, from its own coordinates only.
void KinematicsNode::publish_tf(const ros::Time& stamp) {
  mbk::JointMotion<double> m;
  std::vector<geometry_msgs::TransformStamped> out;
  out.reserve(moving_.size());
  for (size_t i = 0; i < moving_.size(); ++i) {
    if (last_tf_stamp_[i] == stamp) continue;  // tf2 rejects repeated stamps
    const mbk::Body& body = model_.bodies[moving_[i]];
    mbk::joint_motion<double>(body.joint, model_.speeds, state_.position.data() + body.q_index,
                              nullptr, m);
    transforms_[i].header.stamp = stamp;
    set_transform(body, m, transforms_[i].transform);
    last_tf_stamp_[i] = stamp;
    out.push_back(transforms_[i]);
  }
  if (!out.empty()) tf_broadcaster_.sendTransform(out);
}

bool KinematicsNode::publish_kinematics(const ros::Time& stamp, mbk::Level level) {
  mbk::forward_kinematics(model_, state_, data_, level);
  for (int k = 1; k <= model_.body_count(); ++k) {
    if (finite(data_, k, level)) continue;
    last_problem_ = "kinematics of body '" + model_.bodies[k].name + "' not finite; dropped";
    ROS_WARN_STREAM_THROTTLE(kThrottle, last_problem_);
    return false;
  }
  const bool full = level == mbk::Level::kAcceleration;
  const bool kinematics = kinematics_pub_ && kinematics_pub_.getNumSubscribers() > 0;
  const bool markers = markers_pub_ && markers_pub_.getNumSubscribers() > 0;
  if (full && (kinematics || markers)) fill_kinematics_msg(stamp);
  if (full && kinematics) kinematics_pub_.publish(kinematics_msg_);
  if (full && markers) publish_markers();
  // Per-body topics: in the body's own frame (so rviz draws them at the body), of its origin O_k.
  for (size_t k = 1; k < twist_pubs_.size(); ++k) {
    const mbk::Mat3<double> s_k0 = data_.rotation[k].transpose();
    if (twist_pubs_[k] && twist_pubs_[k].getNumSubscribers() > 0) {
      geometry_msgs::TwistStamped t;
      t.header.stamp = stamp;
      t.header.frame_id = model_.bodies[k].name;
      set_vector(s_k0 * data_.omega[k], t.twist.angular);
      set_vector(s_k0 * data_.origin_velocity[k], t.twist.linear);
      twist_pubs_[k].publish(t);
    }
    if (full && accel_pubs_[k] && accel_pubs_[k].getNumSubscribers() > 0) {
      geometry_msgs::AccelStamped a;
      a.header.stamp = stamp;
      a.header.frame_id = model_.bodies[k].name;
      set_vector(s_k0 * data_.alpha[k], a.accel.angular);
      set_vector(s_k0 * data_.origin_acceleration[k], a.accel.linear);
      accel_pubs_[k].publish(a);
    }
  }
  return true;
}

void KinematicsNode::fill_kinematics_msg(const ros::Time& stamp) {
  kinematics_msg_.header.stamp = stamp;
  for (int k = 1; k <= model_.body_count(); ++k) {
    auto& b = kinematics_msg_.bodies[k - 1];
    set_vector(data_.origin[k], b.pose.position);
    const Eigen::Quaterniond q(data_.rotation[k]);
    b.pose.orientation.x = q.x();
    b.pose.orientation.y = q.y();
    b.pose.orientation.z = q.z();
    b.pose.orientation.w = q.w();
    set_vector(data_.mass_center[k], b.mass_center);
    set_vector(data_.omega[k], b.twist.angular);
    set_vector(data_.mass_center_velocity[k], b.twist.linear);
    set_vector(data_.alpha[k], b.accel.angular);
    set_vector(data_.mass_center_acceleration[k], b.accel.linear);
  }
}

// The rviz display's picture as markers, each quantity auto-scaled (largest arrow 0.3 m).
void KinematicsNode::publish_markers() {
  GlyphStyle& style = marker_style_;
  for (int q = 0; q < GlyphQuantity::kCount; ++q)
    style.scale[q] = marker_scales_[q].update(max_norm(kinematics_msg_, style, q), 0.3);
  markers_pub_.publish(
      make_marker_array(make_glyphs(kinematics_msg_, style), style, kinematics_msg_.header));
}

void KinematicsNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - window_start_).count();
  const double rate = elapsed > 0 ? window_.received / elapsed : 0.0;
  const double mean = window_.published ? window_.update_seconds / window_.published : 0.0;
  status.add("input rate (Hz)", rate);
  status.add("update time per sample, mean (us)", mean * 1e6);
  status.add("update time per sample, max (us)", window_.max_update_seconds * 1e6);
  status.add("samples received", total_.received);
  status.add("samples published", total_.published);
  status.add("samples dropped (bad input)", total_.dropped);
  status.add("samples waiting for joints", total_.incomplete);
  status.add("last problem", last_problem_.empty() ? "none" : last_problem_);
  // Cheap error indicators (mb_kinematics/core/error_indicators.h; README, work-precision).
  status.add("rotation orthonormality drift", mbk::orthonormality_drift(data_));
  status.add("Euler parameter norm error", mbk::euler_norm_error(model_, state_));
  status.add("estimator residual, max (rad or m)", window_.max_residual);
  status.add("acceleration estimator", params_.acceleration_estimator);
  if (window_.dropped > 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "dropping samples: " + last_problem_);
  else if (window_.received == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no joint_states received");
  else if (window_.published == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, last_problem_);
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "publishing");
  window_ = Counters();
  window_start_ = now;
}

}  // namespace mbk_ros
