#include "mb_kinematics/estimation/base_odometry_buffer.h"

#include <algorithm>
#include <cmath>

namespace mbk {
namespace {

constexpr size_t kKeep = 256;  // samples kept (after trimming; at most twice as many)

}  // namespace

std::string check_base_sample(const BaseSample& s) {
  if (!(std::isfinite(s.t) && s.position.allFinite() && s.orientation.coeffs().allFinite() &&
        s.linear.allFinite() && s.angular.allFinite()))
    return "NaN or infinite value in the odometry";
  if (s.orientation.squaredNorm() < 1e-12) return "odometry orientation of near-zero norm";
  return "";
}

BaseOdometryBuffer::BaseOdometryBuffer(const DerivativeEstimator& prototype, double max_gap)
    : max_gap_(max_gap) {
  for (auto& e : estimators_) e = prototype.clone();
}

void BaseOdometryBuffer::reset() {
  samples_.clear();
  linear_acceleration_.clear();
  angular_acceleration_.clear();
  valid_.clear();
  for (auto& e : estimators_) e->reset();
}

// Keeps the newest kKeep samples once twice as many have come (amortized O(1) per sample).
void BaseOdometryBuffer::trim() {
  if (samples_.size() < 2 * kKeep) return;
  const auto drop = static_cast<std::ptrdiff_t>(samples_.size() - kKeep);
  samples_.erase(samples_.begin(), samples_.begin() + drop);
  linear_acceleration_.erase(linear_acceleration_.begin(), linear_acceleration_.begin() + drop);
  angular_acceleration_.erase(angular_acceleration_.begin(), angular_acceleration_.begin() + drop);
  valid_.erase(valid_.begin(), valid_.begin() + drop);
}

std::string BaseOdometryBuffer::add(const BaseSample& input) {
  const std::string error = check_base_sample(input);
  if (!error.empty()) return error;
  if (!samples_.empty() && (input.t < last_stamp() || input.t - last_stamp() > max_gap_))
    reset();  // a bag looping, or a pause: nothing interpolated or differentiated across it
  if (!samples_.empty() && input.t == last_stamp()) {
    samples_.pop_back();
    linear_acceleration_.pop_back();
    angular_acceleration_.pop_back();
    valid_.pop_back();
  }
  BaseSample s = input;
  s.orientation.normalize();
  const Vec3<double> v = s.orientation * s.linear, w = s.orientation * s.angular;  // in R
  Vec3<double> a, alpha;
  bool valid = true;
  for (int i = 0; i < 6; ++i) {
    estimators_[i]->add(s.t, i < 3 ? v[i] : w[i - 3]);
    double first = 0, second = 0;
    valid = estimators_[i]->estimate(first, second) >= 1 && valid;
    (i < 3 ? a[i] : alpha[i - 3]) = first;
  }
  samples_.push_back(s);
  linear_acceleration_.push_back(valid ? a : Vec3<double>::Zero());
  angular_acceleration_.push_back(valid ? alpha : Vec3<double>::Zero());
  valid_.push_back(valid);
  trim();
  return "";
}

BaseOdometryBuffer::Fit BaseOdometryBuffer::at(double t, BaseMotion& out, bool& has_acceleration,
                                               bool extrapolate) const {
  if (samples_.empty()) return Fit::kEmpty;
  if (t < first_stamp() - max_gap_) return Fit::kTooOld;
  if (t > last_stamp() + max_gap_) return Fit::kTooNew;
  if (t < first_stamp() || t > last_stamp()) {  // beyond the ends: the nearest sample's motion
    const size_t i = t < first_stamp() ? 0 : samples_.size() - 1;
    has_acceleration = valid_[i];
    const double dt = extrapolate ? t - samples_[i].t : 0;
    extrapolate_base(samples_[i], linear_acceleration_[i], angular_acceleration_[i], dt, out);
    return extrapolate ? Fit::kExtrapolated : Fit::kHeld;
  }
  interpolate_base(samples_, linear_acceleration_, angular_acceleration_, t, out);
  const auto after = std::lower_bound(samples_.begin(), samples_.end(), t,
                                      [](const BaseSample& s, double x) { return s.t < x; });
  const size_t j = after - samples_.begin(), i = j == 0 ? 0 : j - 1;
  has_acceleration = valid_[i] && valid_[j];
  return Fit::kInterpolated;
}

}  // namespace mbk
