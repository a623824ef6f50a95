#include "mb_kinematics/ros/coordinate_coverage.h"

#include "mb_kinematics/core/known_bodies.h"

namespace mbk_ros {

std::string join_names(const std::vector<std::string>& names, size_t max) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < max; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > max) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

CoordinateCoverage::CoordinateCoverage(const mbk::Model& model, MissingCoordinates mode)
    : model_(model),
      mode_(mode),
      is_mimic_(model.nq, 0),
      fresh_(model.nq, 0),
      from_input_(model.nq, 0),
      published_(model.body_count() + 1, 1),
      joined_(model.nq, 0),
      freshness_(model.nq, JointStateInput::Freshness::kNever) {
  for (const mbk::Mimic& m : model.mimics) is_mimic_[m.coordinate] = 1;
}

bool CoordinateCoverage::update(const JointStateInput& input, double t) {
  // Every coordinate fresh now, and joined and from the input before: nothing changes.
  if (all_joined_ && input.every_coordinate_at(t)) return false;
  const bool skip = mode_ == MissingCoordinates::kSkip;
  bool named = false, joins = false;  // what changed: no allocation unless something did
  bool all_joined = true;
  for (int i = 0; i < model_.nq; ++i) {
    if (is_mimic_[i]) continue;  // known_bodies takes them from their sources
    const JointStateInput::Freshness f = input.freshness(i, t);
    named = named || f != freshness_[i];
    freshness_[i] = f;
    const bool fresh = f == JointStateInput::Freshness::kFresh;
    const bool joined = fresh && (!skip || !started_ || joined_[i] || input.settled(i));
    joins = joins || joined != joined_[i];
    joined_[i] = joined;
    // skip: the joined ones only; wait, zero: all received (stale held), not the invented ones
    from_input_[i] = skip ? joined : f != JointStateInput::Freshness::kNever;
    all_joined = all_joined && fresh && joined && from_input_[i];
  }
  all_joined_ = all_joined;
  started_ = true;
  if (!named && !joins) return false;
  std::vector<std::string> never, stale;
  for (int i = 0; i < model_.nq; ++i) {
    if (is_mimic_[i]) continue;
    if (freshness_[i] == JointStateInput::Freshness::kNever)
      never.push_back(model_.coordinate_names[i]);
    if (freshness_[i] == JointStateInput::Freshness::kStale)
      stale.push_back(model_.coordinate_names[i]);
  }
  named = never != never_ || stale != stale_;
  never_ = std::move(never);
  stale_ = std::move(stale);
  fresh_ = joined_;                            // same size: no allocation
  mbk::known_bodies(model_, fresh_, placed_);  // the bodies placed by joined coordinates alone
  affected_.clear();
  for (int k = 1; k <= model_.body_count(); ++k)
    if (!placed_[k]) affected_.push_back(model_.bodies[k].name);
  if (skip) {
    published_ = placed_;
    left_out_ = affected_;
  }
  description_ = describe_missing();
  return named;
}

std::string CoordinateCoverage::describe_missing() const {
  std::string out;
  const std::string bodies = join_names(affected_);
  if (!never_.empty()) {
    out += "joints never received: " + join_names(never_);
    if (mode_ == MissingCoordinates::kWait) out += "; nothing published until they come";
    if (mode_ == MissingCoordinates::kZero)
      out +=
          "; taken as 0 (Euler parameters: identity) until they come, so these bodies are "
          "computed from invented values: " +
          bodies;
  }
  if (!stale_.empty()) {
    out += std::string(out.empty() ? "" : "; ") + "joints without a sample for more than " +
           "~max_sample_gap: " + join_names(stale_);
    if (mode_ != MissingCoordinates::kSkip) out += "; their last values held (stale)";
  }
  if (mode_ == MissingCoordinates::kSkip && !out.empty())  // else: joining, not missing
    out +=
        "; bodies left out of /tf, body_kinematics (its system not filled) and the per-body "
        "topics until they come: " +
        bodies;
  return out;
}

}  // namespace mbk_ros
