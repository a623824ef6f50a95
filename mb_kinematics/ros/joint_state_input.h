// sensor_msgs/JointState into the core's JointState (doc/method.md 8): names
// matched to coordinates, partial messages from several publishers merged per coordinate,
// mimic coordinates filled by mbk::apply_mimics, and velocities and accelerations that the
// messages do not carry estimated per coordinate from its own successive samples; and the
// pairing of joint_states samples with the joint_accelerations of their stamp.
#pragma once

#include <mb_kinematics_msgs/JointAccelerations.h>
#include <sensor_msgs/JointState.h>

#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/joint_state_intake.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/estimation/derivative_estimator.h"
#include "mb_kinematics/estimation/estimator_bank.h"
#include "mb_kinematics/ros/acceleration_pairing.h"
#include "mb_kinematics/ros/input_problem.h"

namespace mbk_ros {

class JointStateInput {
 public:
  // `model` must use coordinate-derivative speeds (nq == nv); it must outlive this object.
  // A coordinate's history restarts when its samples are more than `max_gap` seconds apart
  // (0: never), so that derivatives are never taken across a pause.
  JointStateInput(const mbk::Model& model, const mbk::DerivativeEstimator& prototype,
                  double max_gap = 0);

  struct Update {
    std::string error;                            // why the message was rejected; empty if merged
    InputProblem problem = InputProblem::kCount;  // the class of `error`
    std::vector<std::string> unknown;  // names that are no coordinate of the model (ignored)
    std::vector<std::string> reset;    // coordinates whose stamp went backwards (history reset)
    // Coordinates whose estimates went non-finite or beyond mbk::kMaxStateMagnitude with this
    // sample: their history restarted from it.
    std::vector<std::string> estimator_reset;
    int flipped = 0;  // Euler-parameter joints negated to stay continuous
    int used = 0;     // coordinates the message set
  };
  // Validates the whole message (lengths, duplicate names, NaN/Inf, and whatever
  // mbk::check_state refuses, such as magnitudes beyond 1e50), then merges it at time t
  // (seconds). A rejected message changes nothing: no estimator ever sees its values.
  Update add(const sensor_msgs::JointState& msg, double t);

  // Converts a joint_accelerations message; returns an error (and leaves `out` unspecified) for
  // unequal lengths, duplicate or unknown names, NaN/Inf. No allocation once `out` has the
  // model's size.
  std::string convert(const mb_kinematics_msgs::JointAccelerations& msg, double t,
                      AccelerationSample& out);

  // joint_accelerations paired with joint_states by stamp (acceleration_pairing.h); the lists
  // returned are valid until the next pair (no allocation per sample).
  using Ready = AccelerationPairing::Ready;
  // A joint_states sample; `pairing`: some joint_accelerations publisher is there. The samples
  // to compute now, oldest first: the pending one (unpaired), then `msg` unless it waits.
  const std::vector<Ready>& pair(const sensor_msgs::JointStateConstPtr& msg, bool pairing) {
    return pairing_.add(msg, pairing);
  }
  // A joint_accelerations message at time t, converted (convert) and kept: the pending sample
  // it completes, if any. `error`: why it was refused (then nothing is kept), else "". No
  // allocation once the pairing keeps its most messages (acceleration_pairing.h).
  const std::vector<Ready>& pair(const mb_kinematics_msgs::JointAccelerations& msg, double t,
                                 std::string& error);
  // The kept accelerations of stamp t (seconds), or null: for fill().
  const AccelerationSample* paired(double t) const { return pairing_.at(t); }

  // Names of the coordinates (mimics aside) that no accepted message has set yet.
  std::vector<std::string> missing() const;

  // Of coordinate i (not a mimic) at time t: never set; its last sample within max_gap of t
  // (or max_gap 0); or older than that (stale: its publisher has stopped, or paused).
  enum class Freshness { kNever, kFresh, kStale };
  Freshness freshness(int i, double t) const {  // inline: asked per coordinate and sample
    const Coordinate& c = coordinates_[i];
    if (!c.has_value) return Freshness::kNever;
    return max_gap_ > 0 && t - c.stamp > max_gap_ ? Freshness::kStale : Freshness::kFresh;
  }
  // The last message taken named every coordinate (mimics too), at time t, and none has come
  // since: every coordinate is fresh at t.
  bool every_coordinate_at(double t) const { return steady_ && every_coordinate_ && t == last_t_; }
  // True once coordinate i's history gives what fill() needs for accelerations: a velocity
  // estimate of given velocities, or two position estimates.
  bool settled(int i) const;

  // Fills `state` up to `level`: positions; velocities as given, else estimated; accelerations
  // from `accelerations` (may be null), else estimated from the given velocities, else from
  // the positions; then the mimic coordinates. Returns the level reached: lower than `level`
  // while some coordinate has too few samples for an estimate. `from_input` (model.nq flags;
  // null: all) picks the coordinates taken from the input; the others (~missing_coordinates)
  // get their last value if any, else the zero configuration (Euler parameters: identity), and
  // zero derivatives, and do not lower the level. `checked` (may be null): set true when every
  // value of `state` is known to pass mbk::check_state without its look (see fill's proof),
  // else false.
  mbk::Level fill(mbk::Level level, const AccelerationSample* accelerations,
                  mbk::JointState<double>& state, const std::vector<char>* from_input = nullptr,
                  bool* checked = nullptr) const;

 private:
  struct Coordinate {
    bool mimic = false, has_value = false, velocity_given = false;
    // The history of the other kind (positions when velocities are given) is reset and has
    // taken nothing since: take() need not reset it again.
    bool other_reset = false;
    double velocity = 0, stamp = 0;  // the position: intake_.last()
  };
  std::string validate(const sensor_msgs::JointState& msg, Update& update);
  std::string check_values(const sensor_msgs::JointState& msg, Update& update);
  bool plainly_bounded(const sensor_msgs::JointState& msg) const;
  bool steady(const sensor_msgs::JointState& msg, double t) const;
  void take_each(const sensor_msgs::JointState& msg, double t, Update& update);
  void take_steady(const sensor_msgs::JointState& msg, double t);
  void take(int j, double t);
  void check_estimates(const sensor_msgs::JointState& msg, double t, Update& update);
  bool fill_every(mbk::Level level, mbk::JointState<double>& state) const;

  const mbk::Model& model_;
  double max_gap_;
  // No mimic and no Euler parameters: a message whose values are bounded needs no trial state
  // (plainly_bounded).
  bool plain_model_ = true;
  mbk::JointStateIntake intake_;              // of joint_states (core/joint_state_intake.h)
  mbk::CoordinateLookup acceleration_names_;  // of joint_accelerations
  std::vector<Coordinate> coordinates_;
  // Each coordinate's history of positions, of given velocities (estimator_bank.h).
  std::unique_ptr<mbk::EstimatorBank> positions_, velocities_;
  // The message being taken: each coordinate's new sample for its history, and 1 where it has
  // one (in the bank of the message's kind: one message gives velocities for all or none).
  std::vector<double> sample_;
  std::vector<char> sampled_;
  // The last message checked was taken (steady_), at last_t_, with velocities or not, setting
  // last_used_ coordinates: every one (every_coordinate_) or not. A message with its names
  // (intake_.same_names) that follows it within max_gap is taken by take_steady.
  bool steady_ = false, last_velocity_given_ = false, every_coordinate_ = false;
  // The message checked last, and the last one taken, was plainly_bounded.
  bool plain_message_ = false, last_plain_ = false;
  double last_t_ = 0;
  int last_used_ = 0;
  mbk::JointState<double> initial_, trial_;  // the state before any sample; a message's values
  AccelerationPairing pairing_;
};

}  // namespace mbk_ros
