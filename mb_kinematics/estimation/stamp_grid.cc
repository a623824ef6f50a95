#include "mb_kinematics/estimation/stamp_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mbk {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// A gap of more periods than this is no grid's (the count of periods stays far inside a long).
constexpr double kMostPeriods = 1e12;

// Stamps within this of their grid times are on it already, to double rounding: not moved.
double double_rounding(double largest_stamp) { return 64 * kEpsilon * largest_stamp; }

}  // namespace

double stamp_grid_tolerance(double period, double largest_stamp, double rounding) {
  return std::max({1e-9, rounding, 1e-6 * period}) + 4 * kEpsilon * largest_stamp;
}

double StampGrid::snap(double t) const {
  if (!moves) return t;
  const long double k = std::round((static_cast<long double>(t) - first_stamp - offset) / period);
  return static_cast<double>(first_stamp + (offset + k * period));
}

bool StampGrid::holds(double t) const {
  if (!found) return false;
  const long double u = static_cast<long double>(t) - first_stamp;
  const long double k = std::round((u - offset) / period);
  return std::abs(u - (offset + k * period)) <= tolerance;
}

void StampGridFit::add(double t) {
  if (n_ == 0) first_ = t;
  if (n_ > 0 && !broken_) {
    const double d = t - last_;
    // The period so far: the first interval, then the mean over the periods counted.
    const double h = k_ > 0 ? (last_ - first_) / k_ : d;
    const double periods = std::round(d / h);
    broken_ = !(periods >= 1 && periods <= kMostPeriods) || std::abs(d - periods * h) > 0.25 * h;
    if (!broken_) k_ += static_cast<long>(periods);
  }
  last_ = t;
  largest_ = std::max(largest_, std::abs(t));
  ++n_;
  if (broken_) return;
  const long double k = k_, u = static_cast<long double>(t) - first_;  // Welford's co-moments
  const long double dk = k - mean_k_;
  mean_k_ += dk / n_;
  const long double du = u - mean_u_;
  mean_u_ += du / n_;
  ckk_ += dk * (k - mean_k_);
  cku_ += dk * (u - mean_u_);
}

bool StampGridFit::fit() {
  fitted_ = n_ >= 3 && !broken_ && ckk_ > 0;
  if (!fitted_) return false;
  b_ = cku_ / ckk_;
  a_ = mean_u_ - b_ * mean_k_;
  fitted_ = b_ > 0;
  return fitted_;
}

void StampGridFit::check(double t) {
  if (!fitted_) return;
  const long double u = static_cast<long double>(t) - first_;
  const long double k = std::round((u - a_) / b_);
  if (!(k > last_k_ && k <= last_k_ + kMostPeriods)) {
    fitted_ = false;
    return;
  }
  last_k_ = static_cast<long>(k);
  worst_ = std::max(worst_, static_cast<double>(std::abs(u - (a_ + k * b_))));
  ++checked_;
}

StampGrid StampGridFit::grid() const {
  StampGrid g;
  g.stamps = n_;
  if (!fitted_ || checked_ != n_) return g;
  g.first_stamp = first_, g.offset = a_, g.period = b_;
  g.tolerance = stamp_grid_tolerance(static_cast<double>(b_), largest_, rounding_);
  g.worst = worst_;
  g.found = worst_ <= g.tolerance;
  g.moves = g.found && worst_ > double_rounding(largest_);
  return g;
}

StampGrid find_stamp_grid(const std::vector<double>& t, double rounding) {
  StampGridFit fit;
  fit.set_rounding(rounding);
  for (double x : t) fit.add(x);
  if (fit.fit())
    for (double x : t) fit.check(x);
  return fit.grid();
}

StampGrid snap_to_stamp_grid(std::vector<double>& t, double rounding) {
  const StampGrid grid = find_stamp_grid(t, rounding);
  if (grid.moves)
    for (double& x : t) x = grid.snap(x);
  return grid;
}

}  // namespace mbk
