#include "mb_kinematics/ros/joint_state_input.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "mb_kinematics/core/state_check.h"

namespace mbk_ros {
namespace {

std::string describe(double x) { return std::isnan(x) ? "NaN" : "Inf"; }

// True if the first `used` derivatives an estimator gives are finite and within what
// mbk::check_state accepts for speeds and accelerations.
bool sound(const mbk::DerivativeEstimator& estimator, int used) {
  double d[2] = {0, 0};
  const int n = std::min(estimator.estimate(d[0], d[1]), used);
  for (int i = 0; i < n; ++i)
    if (!(std::abs(d[i]) <= mbk::kMaxStateMagnitude)) return false;  // NaN too
  return true;
}

// The node's class of a sample the intake refused.
InputProblem problem_of(mbk::SampleProblem problem) {
  switch (problem) {
    case mbk::SampleProblem::kUnequalLengths:
      return InputProblem::kUnequalLengths;
    case mbk::SampleProblem::kDuplicateName:
      return InputProblem::kDuplicateName;
    case mbk::SampleProblem::kNonFinite:
    case mbk::SampleProblem::kNone:
      break;
  }
  return InputProblem::kNonFinite;
}

}  // namespace

JointStateInput::JointStateInput(const mbk::Model& model, const mbk::DerivativeEstimator& prototype,
                                 double max_gap)
    : model_(model),
      max_gap_(max_gap),
      intake_(model),
      acceleration_names_(model),
      coordinates_(model.nq),
      initial_(model),
      trial_(model) {
  if (model.nq != model.nv)
    throw std::invalid_argument("JointStateInput needs coordinate-derivative speeds");
  for (int i = 0; i < model.nq; ++i) {
    coordinates_[i].position_history = prototype.clone();
    coordinates_[i].velocity_history = prototype.clone();
  }
  for (const mbk::Mimic& m : model.mimics) coordinates_[m.coordinate].mimic = true;
  plain_model_ = model.mimics.empty();
  for (int k = 1; k <= model.body_count(); ++k)
    plain_model_ = plain_model_ && !mbk::uses_euler_parameters(model.bodies[k].joint.type);
}

// The message checked whole (mbk::JointStateIntake: lengths, duplicate names, NaN/Inf), then
// its values (check_values).
std::string JointStateInput::validate(const sensor_msgs::JointState& msg, Update& update) {
  const std::string error = intake_.check(msg.name, msg.position, msg.velocity);
  if (!error.empty()) {
    update.problem = problem_of(intake_.problem());
    return error;
  }
  update.unknown = intake_.unknown();
  return check_values(msg, update);
}

// True if check_values would find nothing, known without a trial state: a model without mimics
// or Euler parameters, and every value of the message (finite where it names a coordinate: the
// intake checked) within mbk::kMaxStateMagnitude. The values it keeps passed when they came, and
// the trial's velocities and accelerations it does not set are zero. One vectorized pass.
bool JointStateInput::plainly_bounded(const sensor_msgs::JointState& msg) const {
  const auto largest = [](const std::vector<double>& x) {
    return x.empty() ? 0.0 : Eigen::Map<const Eigen::ArrayXd>(x.data(), x.size()).abs().maxCoeff();
  };
  return plain_model_ && largest(msg.position) <= mbk::kMaxStateMagnitude &&
         largest(msg.velocity) <= mbk::kMaxStateMagnitude;
}

// What mbk::check_state would refuse, before any estimator sees it: the message's values over
// the coordinates known so far (mimics applied).
std::string JointStateInput::check_values(const sensor_msgs::JointState& msg, Update& update) {
  if (plainly_bounded(msg)) return "";
  for (int i = 0; i < model_.nq; ++i)
    trial_.position[i] =
        coordinates_[i].has_value ? coordinates_[i].position : initial_.position[i];
  trial_.velocity.setZero();
  trial_.acceleration.setZero();
  for (size_t i = 0; i < msg.name.size(); ++i) {
    const int j = intake_.coordinates()[i];
    if (j < 0 || coordinates_[j].mimic) continue;
    trial_.position[j] = msg.position[i];
    if (!msg.velocity.empty()) trial_.velocity[j] = msg.velocity[i];
  }
  mbk::apply_mimics(model_, trial_);
  const std::string error = mbk::check_state(model_, trial_);
  if (error.find("Euler parameters") != std::string::npos)
    update.problem = InputProblem::kNotARotation;
  else if (error.find("not finite") != std::string::npos)
    update.problem = InputProblem::kNonFinite;  // e.g. a mimic's multiplier overflowing
  else
    update.problem = InputProblem::kTooLarge;
  return error;
}

JointStateInput::Update JointStateInput::add(const sensor_msgs::JointState& msg, double t) {
  Update update;
  update.error = validate(msg, update);
  if (!update.error.empty()) return update;
  update.flipped = intake_.take(msg.position);  // e and -e: one rotation, e kept continuous
  for (size_t i = 0; i < msg.name.size(); ++i) {
    const int j = intake_.coordinates()[i];
    if (j < 0) continue;  // a published mimic value wins over its rule (robot_state_publisher)
    Coordinate& c = coordinates_[j];
    if (c.has_value && t < c.stamp) {  // e.g. a bag looping: the old history means nothing
      c.position_history->reset();
      c.velocity_history->reset();
      update.reset.push_back(msg.name[i]);
    } else if (c.has_value && max_gap_ > 0 && t - c.stamp > max_gap_) {  // a pause
      c.position_history->reset();
      c.velocity_history->reset();
    }
    const bool velocity_given = !msg.velocity.empty();
    c.other_reset = c.other_reset && c.has_value && velocity_given == c.velocity_given;
    c.has_value = true;
    c.position = intake_.last()[j];
    c.velocity_given = velocity_given;
    if (c.velocity_given) c.velocity = intake_.sign(j) * msg.velocity[i];
    if (!take(c, t)) update.estimator_reset.push_back(msg.name[i]);
    ++update.used;
  }
  return update;
}

// Adds the coordinate's new sample at t to the estimator of its derivatives: that of the given
// velocities when the message has them, else that of the positions; the other starts again (a
// gap in its stream). An estimator whose estimates go non-finite or beyond what check_state
// accepts (an angle of 1e300 rad, say, is a valid angle but no motion) restarts from this
// sample: false then.
bool JointStateInput::take(Coordinate& c, double t) {
  c.stamp = t;
  mbk::DerivativeEstimator& used = c.velocity_given ? *c.velocity_history : *c.position_history;
  if (!c.other_reset) (c.velocity_given ? c.position_history : c.velocity_history)->reset();
  c.other_reset = true;
  const double value = c.velocity_given ? c.velocity : c.position;
  used.add(t, value);
  if (sound(used, c.velocity_given ? 1 : 2)) return true;
  used.reset();
  used.add(t, value);
  return false;
}

std::string JointStateInput::convert(const mb_kinematics_msgs::JointAccelerations& msg, double t,
                                     AccelerationSample& out) {
  if (msg.acceleration.size() != msg.name.size())
    return std::to_string(msg.name.size()) + " names but " +
           std::to_string(msg.acceleration.size()) + " accelerations";
  out.stamp = t;
  out.value.assign(model_.nq, 0.0);
  out.given.assign(model_.nq, 0);
  const std::vector<int>& index = acceleration_names_.look_up(msg.name);
  for (size_t i = 0; i < msg.name.size(); ++i) {
    const int j = index[i];
    if (j < 0) return "joint '" + msg.name[i] + "' is not in the model";
    if (out.given[j]) return "joint '" + msg.name[i] + "' is named twice";
    if (!std::isfinite(msg.acceleration[i]))
      return "joint '" + msg.name[i] + "': acceleration is " + describe(msg.acceleration[i]);
    out.given[j] = 1;
    out.value[j] = msg.acceleration[i];
  }
  return "";
}

const std::vector<JointStateInput::Ready>& JointStateInput::pair(
    const mb_kinematics_msgs::JointAccelerations& msg, double t, std::string& error) {
  static const std::vector<Ready> kNone;
  error = convert(msg, t, pairing_.next());
  if (!error.empty()) return kNone;
  return pairing_.add_next();
}

std::vector<std::string> JointStateInput::missing() const {
  std::vector<std::string> names;
  for (int i = 0; i < model_.nq; ++i)
    if (!coordinates_[i].mimic && !coordinates_[i].has_value)
      names.push_back(model_.coordinate_names[i]);
  return names;
}

bool JointStateInput::settled(int i) const {
  const Coordinate& c = coordinates_[i];
  double first = 0, second = 0;
  if (c.velocity_given) return c.velocity_history->estimate(first, second) >= 1;
  return c.position_history->estimate(first, second) >= 2;
}

mbk::Level JointStateInput::fill(mbk::Level level, const AccelerationSample* accelerations,
                                 mbk::JointState<double>& state,
                                 const std::vector<char>* from_input) const {
  bool velocities = level != mbk::Level::kPose;
  bool accels = level == mbk::Level::kAcceleration;
  for (int i = 0; i < model_.nq; ++i) {
    const Coordinate& c = coordinates_[i];
    if (c.mimic && !c.has_value) continue;  // the mimic rule, below
    if (from_input && !(*from_input)[i] &&
        !c.mimic) {  // ~missing_coordinates: held or zero, at rest
      state.position[i] = c.has_value ? c.position : initial_.position[i];
      state.velocity[i] = state.acceleration[i] = 0;
      continue;
    }
    state.position[i] = c.position;
    double first = 0, second = 0;  // the positions' estimates, when no velocity is given
    const int n = c.velocity_given ? 0 : c.position_history->estimate(first, second);
    if (velocities) {
      state.velocity[i] = c.velocity_given ? c.velocity : first;
      velocities = c.velocity_given || n >= 1;
    }
    if (!accels) continue;
    if (accelerations && accelerations->given[i]) {
      state.acceleration[i] = accelerations->value[i];
    } else if (c.velocity_given) {
      double v_second = 0;
      accels = c.velocity_history->estimate(state.acceleration[i], v_second) >= 1;
    } else {
      state.acceleration[i] = second;
      accels = n >= 2;
    }
  }
  for (const mbk::Mimic& m : model_.mimics)  // in order: a mimic of a mimic reads the result
    if (!coordinates_[m.coordinate].has_value) mbk::apply_mimic(m, state);
  if (!velocities) return mbk::Level::kPose;
  return accels ? mbk::Level::kAcceleration : mbk::Level::kVelocity;
}

}  // namespace mbk_ros
