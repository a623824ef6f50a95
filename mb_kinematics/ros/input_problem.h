// The classes of input the node drops, repairs or waits on, each counted on /diagnostics so
// that an operator sees what was refused and why (doc/node.md: bad input).
#pragma once

namespace mbk_ros {

enum class InputProblem {
  // joint_states samples dropped whole
  kUnequalLengths,       // names, positions, velocities of unequal length
  kDuplicateName,        // a coordinate named twice
  kNonFinite,            // NaN or Inf
  kTooLarge,             // beyond mbk::kMaxStateMagnitude (1e50): mbk::check_state
  kNotARotation,         // Euler parameters of near-zero norm: mbk::check_state
  kNoBaseMotion,         // ~base_odometry: no odometry within the gap of the sample's stamp
  kKinematicsNotFinite,  // the kinematics of some body came out non-finite
  // ignored
  kNoKnownName,       // empty, or no coordinate of the model named
  kBadAccelerations,  // a joint_accelerations message refused
  kBadOdometry,       // a ~base_odometry message refused (NaN/Inf, another frame_id)
  // repaired: the sample is used
  kUnknownName,     // names not in the model, ignored
  kZeroStamp,       // stamp 0: the time of arrival used
  kStampBackwards,  // estimators restarted (a bag looping)
  kEstimatorReset,  // an estimate went beyond 1e50 or non-finite: that coordinate restarted
  kEulerSignFlip,   // Euler parameters negated to stay continuous
  kUnpaired,        // its joint_accelerations never came: accelerations estimated
  // ~base_odometry: no odometry after the sample's stamp within ~base_odometry_wait
  kBaseHeld,          // the base's last odometry held
  kBaseExtrapolated,  // ~base_odometry_extrapolate: its twist carried on to the stamp
  // waiting
  kMissingJoints,  // some coordinate never received: nothing published yet
  kNoOdometry,     // ~base_odometry: no odometry received yet, R unknown: nothing published
  // published with what ~missing_coordinates makes of the coordinates missing (doc/node.md)
  kBodiesLeftOut,  // skip: the bodies of coordinates never received or stale left out
  kZeroed,         // zero: coordinates never received taken as 0
  kStaleHeld,      // wait, zero: coordinates without a sample for ~max_sample_gap held
  kCount
};

// The /diagnostics key, e.g. "dropped: NaN or Inf".
const char* diagnostic_key(InputProblem problem);

// True for the classes whose sample is lost (dropped whole).
bool drops_sample(InputProblem problem);

}  // namespace mbk_ros
