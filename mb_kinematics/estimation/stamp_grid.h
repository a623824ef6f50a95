// Stamps that lie on a uniform grid t0 + k h to within their resolution: a recording sampled on
// an exact grid but written with rounded stamps (a bag's nanoseconds: rospy.Time.from_sec cuts
// up to 1 ns off each) is differentiated on the grid's times, since twice differentiated the
// rounding alone would dominate the accelerations. Stamps with real jitter are left as they are.
// Found in two passes over the stamps in order (so a recording read a row at a time needs no
// copy of them): add() each, fit(), check() each. ROS-free.
#pragma once

#include <vector>

namespace mbk {

// The grid found (or not) and how far it moved the stamps.
struct StampGrid {
  bool found = false;  // every stamp within tolerance of origin + k period
  bool moves = false;  // found, and some stamp is off its grid time by more than double rounding
  // Grid time k is first_stamp + (offset + k period): offset and period fitted by least squares
  // over every stamp (k counts periods from the first stamp, gaps included). The offset is the
  // stamps' mean rounding (-0.5 ns for from_sec's truncation): a constant shift of every time.
  double first_stamp = 0;
  long double offset = 0, period = 0;
  double tolerance = 0;  // what `found` allowed
  double worst = 0;      // the largest |stamp - its grid time|
  long stamps = 0;
  // The grid time nearest t (t itself when the grid does not move the stamps).
  double snap(double t) const;
  // t is within the tolerance of a grid time (of a found grid).
  bool holds(double t) const;
};

// The grid's period where the stamps lie on one (found), else 0: Segments::period
// (estimation/offline_estimator.h).
inline double grid_period(const StampGrid& g) {
  return g.found ? static_cast<double>(g.period) : 0;
}

// The stamps' distance allowed from the grid: max(1 ns, `rounding`, 1e-6 h) plus 4 x 2.2e-16 x
// the largest |stamp| (a stamp in double seconds far from 0 is rounded to that). rounding: the
// stamps' own (half a unit of the last decimal a text gives them), 0 for none beyond a bag's ns.
double stamp_grid_tolerance(double period, double largest_stamp, double rounding = 0);

class StampGridFit {
 public:
  void add(double t);  // first pass: the stamps in increasing order
  void set_rounding(double rounding) { rounding_ = rounding; }  // as stamp_grid_tolerance's
  // After the first pass: false when the stamps cannot lie on a grid (fewer than 3, or an
  // interval that is not a whole number of periods): no second pass is needed.
  bool fit();
  void check(double t);  // second pass: the same stamps in the same order
  StampGrid grid() const;

 private:
  long n_ = 0, checked_ = 0;
  double first_ = 0, last_ = 0, largest_ = 0;
  long k_ = 0;           // the index of the last stamp added
  bool broken_ = false;  // an interval not a whole number of periods
  // Running least squares of u = t - t0 on k, in long double: a fit in double drifts by 1e-13 s
  // over 20,000 stamps, more than the rounding of stamps already on their grid.
  long double mean_k_ = 0, mean_u_ = 0, ckk_ = 0, cku_ = 0;
  long double a_ = 0, b_ = 0;  // u = a + b k
  long last_k_ = -1;
  double worst_ = 0, rounding_ = 0;
  bool fitted_ = false;
};

// Both passes over a vector of increasing stamps.
StampGrid find_stamp_grid(const std::vector<double>& t, double rounding = 0);
// Every stamp moved to its grid time when the grid moves them; returns the grid.
StampGrid snap_to_stamp_grid(std::vector<double>& t, double rounding = 0);

}  // namespace mbk
