#include "mb_kinematics/core/joint_state_intake.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace mbk {
namespace {

std::string describe(double x) { return std::isnan(x) ? "NaN" : "Inf"; }

std::string lengths(size_t names, size_t values, const char* what) {
  return std::to_string(names) + " names but " + std::to_string(values) + " " + what;
}

// Every value finite, in one vectorized pass (x * 0 sums to NaN if some x is Inf or NaN): the
// common sample, whose values then need no look at each name.
bool all_finite(const std::vector<double>& x) {
  return x.empty() || (Eigen::Map<const Eigen::ArrayXd>(x.data(), x.size()) * 0.0).sum() == 0.0;
}

// The first `n` bytes at p and at q equal, for the short strings of joint names: eight bytes at a
// time and the last eight (overlapping), or the first and last four, two, or the one byte,
// inline; std::string's == calls memcmp for each name (a sample's names are compared whole).
bool same_bytes(const char* p, const char* q, size_t n) {
  const auto same = [p, q](size_t at, auto word) {
    decltype(word) a, b;
    std::memcpy(&a, p + at, sizeof a);
    std::memcpy(&b, q + at, sizeof b);
    return a == b;
  };
  if (n >= 8) {
    for (size_t i = 0; i + 8 <= n; i += 8)
      if (!same(i, uint64_t())) return false;
    return same(n - 8, uint64_t());
  }
  if (n >= 4) return same(0, uint32_t()) && same(n - 4, uint32_t());
  if (n >= 2) return same(0, uint16_t()) && same(n - 2, uint16_t());
  return n == 0 || p[0] == q[0];
}

// a == b, name by name with same_bytes.
bool same_names(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].size() != b[i].size() || !same_bytes(a[i].data(), b[i].data(), a[i].size()))
      return false;
  return true;
}

}  // namespace

CoordinateLookup::CoordinateLookup(const Model& model) {
  for (int i = 0; i < model.nq; ++i) index_[model.coordinate_names[i]] = i;
}

const std::vector<int>& CoordinateLookup::look_up(const std::vector<std::string>& names,
                                                  bool* changed) {
  const bool differ = !same_names(names, names_);  // a full compare: cheaper than hashing each
  if (changed) *changed = differ;
  if (!differ) return coordinate_of_;
  names_ = names;
  coordinate_of_.resize(names.size());
  for (size_t i = 0; i < names.size(); ++i) {
    auto it = index_.find(names[i]);
    coordinate_of_[i] = it == index_.end() ? -1 : it->second;
  }
  return coordinate_of_;
}

JointStateIntake::JointStateIntake(const Model& model)
    : model_(model),
      lookup_(model),
      place_(model.nq, -1),
      sign_(model.nq, 1.0),
      last_(model.nq, 0.0),
      taken_(model.nq, 0) {
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    if (uses_euler_parameters(body.joint.type))
      euler_.push_back(body.q_index + first_euler_parameter(body.joint.type));
  }
}

// unknown_, place_ and duplicate_at_ for new names (coordinate_of_ looked up).
void JointStateIntake::map_names(const std::vector<std::string>& names) {
  unknown_.clear();
  std::fill(place_.begin(), place_.end(), -1);
  duplicate_at_ = names.size();
  for (size_t i = 0; i < names.size(); ++i) {
    const int c = lookup_.coordinates()[i];
    if (c < 0)
      unknown_.push_back(names[i]);
    else if (place_[c] < 0)
      place_[c] = static_cast<int>(i);
    else if (duplicate_at_ == names.size())
      duplicate_at_ = i;
  }
}

std::string JointStateIntake::check(const std::vector<std::string>& names,
                                    const std::vector<double>& position,
                                    const std::vector<double>& velocity) {
  const size_t n = names.size();
  same_names_ = false;
  problem_ = SampleProblem::kUnequalLengths;
  if (position.size() != n) return lengths(n, position.size(), "positions");
  if (!velocity.empty() && velocity.size() != n) return lengths(n, velocity.size(), "velocities");
  bool changed = false;
  const std::vector<int>& coordinate_of = lookup_.look_up(names, &changed);
  if (changed) map_names(names);
  same_names_ = !changed;
  problem_ = SampleProblem::kNone;
  if (duplicate_at_ == n && all_finite(position) && all_finite(velocity)) return "";
  for (size_t i = 0; i < n; ++i) {  // the first problem in the sample's order
    problem_ = SampleProblem::kDuplicateName;
    if (i == duplicate_at_) return "joint '" + names[i] + "' is named twice";
    if (coordinate_of[i] < 0) continue;
    problem_ = SampleProblem::kNonFinite;
    if (!std::isfinite(position[i]))
      return "joint '" + names[i] + "': position is " + describe(position[i]);
    if (!velocity.empty() && !std::isfinite(velocity[i]))
      return "joint '" + names[i] + "': velocity is " + describe(velocity[i]);
  }
  problem_ = SampleProblem::kNone;
  return "";
}

int JointStateIntake::take(const std::vector<double>& position) {
  int flipped = 0;
  for (const int e : euler_) {
    double dot = 0;
    bool all = true;
    for (int i = e; i < e + 4; ++i) {
      all = all && place_[i] >= 0 && taken_[i];
      if (all) dot += position[place_[i]] * last_[i];
    }
    const bool flip = all && dot < 0;
    for (int i = e; i < e + 4; ++i) sign_[i] = flip ? -1.0 : 1.0;
    flipped += flip;
  }
  // The arrays' starts in locals (read once, not again after each store); without Euler
  // parameters every sign is 1 and the positions are taken as they are (1 * x is x).
  const int* place = place_.data();
  const double* sign = sign_.data();
  double* last = last_.data();
  char* taken = taken_.data();
  if (euler_.empty()) {
    for (int i = 0; i < model_.nq; ++i)
      if (place[i] >= 0) last[i] = position[place[i]], taken[i] = 1;
    return flipped;
  }
  for (int i = 0; i < model_.nq; ++i)
    if (place[i] >= 0) last[i] = sign[i] * position[place[i]], taken[i] = 1;
  return flipped;
}

}  // namespace mbk
