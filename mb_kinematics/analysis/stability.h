// Numerical stability on stiff and extreme cases (doc/stability.md): the forward
// error of the double recursion against the same recursion in higher precision on the same
// double inputs (cast exactly), measured against the scale of the terms that the recursion
// sums, per body and per link of depth. test/stability/ asserts the bounds; mbk_stability_report
// prints the table.
//
// The analysis. Every quantity of body k is formed, link by link along its path, as a sum of
// terms (doc/method.md 4): S0K = S0J SJK; o_k = o_j + S0J (q_k + s_k); omega_k = omega_j + S0J w_k;
// v, alpha, a likewise. Each link adds at most c roundings of terms of the scale of the sum's
// terms: sin/cos (glibc: < 1 ulp) 2 eps, a rotation entry (product of three, one sum) <= 9
// eps, the product S0J SJK (sums of three) 3 eps more: <= 12 eps per entry, <= 21 eps in
// Frobenius norm per link; a vector term (matrix-vector 3 eps, nested cross products 4 eps) and
// the sum of <= 6 terms (6 eps), plus the inherited S0J error (<= 21 eps per ancestor link):
// c = 40 per link covers both. So |Q_k - Q_k,exact| <= c * depth_k * eps * T_k, where T_k is
// the sum of the magnitudes of the terms (term_scales below), eps = 2^-53. This is a worst
// case (errors of one sign); random errors grow like sqrt(depth). The bounds asserted are
// kSafety = 4 times it: kLinkBound = 4 * 40 * eps per link, relative to T_k. An error relative
// to |Q_k| itself can be larger by T_k / |Q_k| when terms cancel: that is the conditioning of
// the problem (a relative change eps of an angle input moves Q_k by ~eps T_k), not a loss in
// the method.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/kinematics_error.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

constexpr double kEps = 0x1p-53;                                   // unit roundoff of double
constexpr double kRoundingsPerLink = 40;                           // c above
constexpr double kSafety = 4;                                      // safety factor on every bound
constexpr double kLinkBound = kSafety * kRoundingsPerLink * kEps;  // ~1.8e-14

// Sums of the magnitudes of the terms of each quantity, per body (index k; 0 is R), and the
// depth of each body (1 for a body on R).
struct TermScales {
  std::array<std::vector<double>, ErrorQuantity::kCount> scale;
  std::vector<int> depth;
};
TermScales term_scales(const Model& model, const JointState<double>& state);

// Error per quantity against the reference: per_link = max_k |Q_k - ref_k| / (T_k * depth_k)
// (compare with kLinkBound); scaled = max_k |Q_k - ref_k| / T_k; relative = kinematics_error
// (against the largest |ref| over the bodies). Orientation: Frobenius norm, T = 1. A quantity
// with T_k = 0 and an error is infinite; a non-finite value is infinite.
struct StabilityError {
  std::array<double, ErrorQuantity::kCount> per_link{}, scaled{}, relative{};
  double max_per_link() const;
};

// Runs the recursion in double and in R on the same inputs and measures the error. R: Quad
// (mb_kinematics/analysis/quad.h) or long double.
template <typename R>
StabilityError stability_error(const Model& model, const JointState<double>& state,
                               Level level = Level::kAcceleration);

// One row of the table: case | quantity | measured | bound | note.
struct StabilityRow {
  std::string group, name, quantity;
  double measured = 0, bound = 0;
  std::string note;
  bool ok() const { return measured <= bound; }
};

// The cases of one group ("gimbal_lock", "euler_parameters", "large_coordinates",
// "mixed_scales", "stiff_motion", "size_shape", "input_extremes", "estimator_time");
// stability_groups() lists them. Each row's bound is derived in stability.cc next to it.
const std::vector<std::string>& stability_groups();
std::vector<StabilityRow> stability_cases(const std::string& group);

// "| case | quantity | measured | bound | note |" rows.
std::string format_stability_table(const std::vector<StabilityRow>& rows);

}  // namespace mbk
