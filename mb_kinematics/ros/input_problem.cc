#include "mb_kinematics/ros/input_problem.h"

namespace mbk_ros {

const char* diagnostic_key(InputProblem problem) {
  switch (problem) {
    case InputProblem::kUnequalLengths:
      return "dropped: arrays of unequal length";
    case InputProblem::kDuplicateName:
      return "dropped: a name twice";
    case InputProblem::kNonFinite:
      return "dropped: NaN or Inf";
    case InputProblem::kTooLarge:
      return "dropped: magnitude above 1e50";
    case InputProblem::kNotARotation:
      return "dropped: Euler parameters of near-zero norm";
    case InputProblem::kNoBaseMotion:
      return "dropped: no base odometry within the gap";
    case InputProblem::kKinematicsNotFinite:
      return "dropped: kinematics not finite";
    case InputProblem::kNoKnownName:
      return "ignored: empty or no name of the model";
    case InputProblem::kBadAccelerations:
      return "ignored: joint_accelerations refused";
    case InputProblem::kBadOdometry:
      return "ignored: base odometry refused";
    case InputProblem::kUnknownName:
      return "repaired: names not in the model ignored";
    case InputProblem::kZeroStamp:
      return "repaired: zero stamp, time of arrival used";
    case InputProblem::kStampBackwards:
      return "repaired: stamp backwards, estimators restarted";
    case InputProblem::kEstimatorReset:
      return "repaired: estimate beyond 1e50 or not finite, coordinate restarted";
    case InputProblem::kEulerSignFlip:
      return "repaired: Euler parameters negated (sign flip)";
    case InputProblem::kUnpaired:
      return "repaired: joint_accelerations missing, estimated";
    case InputProblem::kBaseHeld:
      return "held: base odometry, none after the sample";
    case InputProblem::kBaseExtrapolated:
      return "extrapolated: base odometry, none after the sample";
    case InputProblem::kMissingJoints:
      return "waiting: joints never received";
    case InputProblem::kNoOdometry:
      return "waiting: base odometry never received";
    case InputProblem::kBodiesLeftOut:
      return "partial: bodies left out (joints never received or stale)";
    case InputProblem::kZeroed:
      return "invented: joints never received taken as 0";
    case InputProblem::kStaleHeld:
      return "stale: joints without a sample for ~max_sample_gap held";
    case InputProblem::kCount:
      break;
  }
  return "unknown";
}

bool drops_sample(InputProblem problem) { return problem <= InputProblem::kKinematicsNotFinite; }

}  // namespace mbk_ros
