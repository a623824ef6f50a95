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
      positions_(prototype.bank(model.nq)),
      velocities_(prototype.bank(model.nq)),
      sample_(model.nq, 0.0),
      sampled_(model.nq, 0),
      initial_(model),
      trial_(model) {
  if (model.nq != model.nv)
    throw std::invalid_argument("JointStateInput needs coordinate-derivative speeds");
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
  plain_message_ = plainly_bounded(msg);
  if (plain_message_) return "";
  for (int i = 0; i < model_.nq; ++i)
    trial_.position[i] = coordinates_[i].has_value ? intake_.last()[i] : initial_.position[i];
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
  const bool steady_message = steady(msg, t);
  steady_ = false;
  if (!update.error.empty()) return update;
  update.flipped = intake_.take(msg.position);  // e and -e: one rotation, e kept continuous
  const bool velocity_given = !msg.velocity.empty();
  if (steady_message)
    take_steady(msg, t);
  else
    take_each(msg, t, update);
  update.used = last_used_;
  // The samples into their histories, all in one call (KalmanBank: one vectorized pass).
  (velocity_given ? velocities_ : positions_)->add(t, sample_.data(), sampled_.data());
  check_estimates(msg, t, update);
  steady_ = true;
  last_t_ = t;
  last_velocity_given_ = velocity_given;
  last_plain_ = plain_message_;
  return update;
}

// The message names the coordinates the last one taken named, in the same order, and of the
// same kind (velocities or not), not before it and within max_gap of it: then each of its
// coordinates was last set by that message, its history takes this sample as it is, and only
// the values change (take_steady).
bool JointStateInput::steady(const sensor_msgs::JointState& msg, double t) const {
  return steady_ && intake_.same_names() && msg.velocity.empty() != last_velocity_given_ &&
         t >= last_t_ && !(max_gap_ > 0 && t - last_t_ > max_gap_);
}

// The values of a steady message: what take_each does to a coordinate that has a value of this
// kind, set at a stamp not after t and within max_gap of it.
void JointStateInput::take_steady(const sensor_msgs::JointState& msg, double t) {
  // The arrays' starts in locals: read once, not again after each store.
  const int* coordinate_of = intake_.coordinates().data();
  const size_t n = intake_.coordinates().size();
  const double* last = intake_.last().data();
  const double* velocity = msg.velocity.data();
  Coordinate* coordinates = coordinates_.data();
  double* sample = sample_.data();
  if (msg.velocity.empty()) {
    for (size_t i = 0; i < n; ++i) {
      const int j = coordinate_of[i];
      if (j < 0) continue;
      coordinates[j].stamp = t;
      sample[j] = last[j];
    }
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    const int j = coordinate_of[i];
    if (j < 0) continue;
    Coordinate& c = coordinates[j];
    c.velocity = intake_.sign(j) * velocity[i];
    c.stamp = t;
    sample[j] = c.velocity;
  }
}

// Each coordinate the message names: its history reset if its stamps went back or paused, its
// value and the sample for its history (take).
void JointStateInput::take_each(const sensor_msgs::JointState& msg, double t, Update& update) {
  const bool velocity_given = !msg.velocity.empty();
  std::fill(sampled_.begin(), sampled_.end(), 0);
  last_used_ = 0;
  for (size_t i = 0; i < msg.name.size(); ++i) {
    const int j = intake_.coordinates()[i];
    if (j < 0) continue;  // a published mimic value wins over its rule (robot_state_publisher)
    Coordinate& c = coordinates_[j];
    if (c.has_value && t < c.stamp) {  // e.g. a bag looping: the old history means nothing
      positions_->reset(j);
      velocities_->reset(j);
      update.reset.push_back(msg.name[i]);
    } else if (c.has_value && max_gap_ > 0 && t - c.stamp > max_gap_) {  // a pause
      positions_->reset(j);
      velocities_->reset(j);
    }
    c.other_reset = c.other_reset && c.has_value && velocity_given == c.velocity_given;
    c.has_value = true;
    c.velocity_given = velocity_given;
    if (c.velocity_given) c.velocity = intake_.sign(j) * msg.velocity[i];
    take(j, t);
    ++last_used_;
  }
  every_coordinate_ = last_used_ == model_.nq;  // no name twice (the intake checked)
}

// Makes the coordinate's new sample at t the next for the history of its derivatives: that of
// the given velocities when the message has them, else that of the positions; the other starts
// again (a gap in its stream).
void JointStateInput::take(int j, double t) {
  Coordinate& c = coordinates_[j];
  c.stamp = t;
  if (!c.other_reset) (c.velocity_given ? positions_ : velocities_)->reset(j);
  c.other_reset = true;
  sample_[j] = c.velocity_given ? c.velocity : intake_.last()[j];
  sampled_[j] = 1;
}

// A history whose estimates went non-finite or beyond what check_state accepts (an angle of
// 1e300 rad, say, is a valid angle but no motion) restarts from this sample, named in
// update.estimator_reset (in the message's order). One pass over the bank when all are sound.
void JointStateInput::check_estimates(const sensor_msgs::JointState& msg, double t,
                                      Update& update) {
  const bool velocity_given = !msg.velocity.empty();
  mbk::EstimatorBank& used = velocity_given ? *velocities_ : *positions_;
  const int derivatives = velocity_given ? 1 : 2;
  if (used.bounded(sampled_.data(), derivatives, mbk::kMaxStateMagnitude)) return;
  for (size_t i = 0; i < msg.name.size(); ++i) {
    const int j = intake_.coordinates()[i];
    if (j < 0 || used.bounded(j, derivatives, mbk::kMaxStateMagnitude)) continue;
    used.reset(j);
    used.add(j, t, sample_[j]);
    update.estimator_reset.push_back(msg.name[i]);
  }
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
  if (c.velocity_given) return velocities_->estimate(i, first, second) >= 1;
  return positions_->estimate(i, first, second) >= 2;
}

// fill() when the last message taken named every coordinate, all from the input, with no
// accelerations given: the values and the banks' estimates copied whole, as fill() would. False
// when an estimate is missing: then `state` holds no value fill() would not write. The positions
// are the intake's last ones; the message's velocities (given) are the samples it put in its
// bank, sample_ (take, take_steady: every coordinate's, as it named them all).
bool JointStateInput::fill_every(mbk::Level level, mbk::JointState<double>& state) const {
  if (level != mbk::Level::kPose && !last_velocity_given_ &&
      !positions_->all_estimated(state.velocity.data(), level == mbk::Level::kAcceleration
                                                            ? state.acceleration.data()
                                                            : nullptr))
    return false;
  std::copy(intake_.last().begin(), intake_.last().end(), state.position.data());
  if (level == mbk::Level::kPose || !last_velocity_given_) return true;
  std::copy(sample_.begin(), sample_.end(), state.velocity.data());
  return level == mbk::Level::kVelocity ||
         velocities_->all_estimated(state.acceleration.data(), nullptr);
}

mbk::Level JointStateInput::fill(mbk::Level level, const AccelerationSample* accelerations,
                                 mbk::JointState<double>& state,
                                 const std::vector<char>* from_input, bool* checked) const {
  if (checked) *checked = false;
  const bool all_from_input =
      !from_input || std::find(from_input->begin(), from_input->end(), 0) == from_input->end();
  if (steady_ && every_coordinate_ && !accelerations && all_from_input &&
      fill_every(level, state)) {
    // Proof that mbk::check_state accepts such a state at kAcceleration (its plainly_valid:
    // every position, velocity and acceleration finite and within kMaxStateMagnitude, and no
    // Euler parameters). The last message taken set every coordinate (every_coordinate_), and
    // last_plain_ says that it was plainly_bounded: a model without mimics or Euler parameters
    // (each position is the message's, sign 1, and there is no |e|^2 to look at), its
    // positions and velocities finite (the intake) and within the bound. fill_every copied
    // those, and the estimates of the bank it took (all_estimated: 3 samples or more for every
    // coordinate) after check_estimates found every used estimate within the bound (bounded:
    // NaN fails it), else it restarted that history and all_estimated failed. At
    // kAcceleration every vector of `state` is written. Tested: JointStateInputPlain,
    // CheckedAsCheckState (test/ros/joint_state_input_test.cc).
    if (checked) *checked = level == mbk::Level::kAcceleration && last_plain_;
    return level;
  }
  bool velocities = level != mbk::Level::kPose;
  bool accels = level == mbk::Level::kAcceleration;
  for (int i = 0; i < model_.nq; ++i) {
    const Coordinate& c = coordinates_[i];
    if (c.mimic && !c.has_value) continue;  // the mimic rule, below
    if (from_input && !(*from_input)[i] &&
        !c.mimic) {  // ~missing_coordinates: held or zero, at rest
      state.position[i] = c.has_value ? intake_.last()[i] : initial_.position[i];
      state.velocity[i] = state.acceleration[i] = 0;
      continue;
    }
    state.position[i] = intake_.last()[i];
    double first = 0, second = 0;  // the positions' estimates, when no velocity is given
    const int n = c.velocity_given ? 0 : positions_->estimate(i, first, second);
    if (velocities) {
      state.velocity[i] = c.velocity_given ? c.velocity : first;
      velocities = c.velocity_given || n >= 1;
    }
    if (!accels) continue;
    if (accelerations && accelerations->given[i]) {
      state.acceleration[i] = accelerations->value[i];
    } else if (c.velocity_given) {
      double v_second = 0;
      accels = velocities_->estimate(i, state.acceleration[i], v_second) >= 1;
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
