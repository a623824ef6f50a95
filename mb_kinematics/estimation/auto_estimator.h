// The automatic offline estimator ("auto", the default of mbk bag): per series, the zero-phase
// local polynomial of estimation/offline_estimator.h whose window is chosen from the data by
// Lepski's principle (Lepski, Mammen & Spokoiny 1997), the data-driven bandwidth choice for
// derivatives: windows of 7 to 641 median intervals are tried shortest first, and a window is
// kept while its estimates (velocities and accelerations, each their own choice) differ from
// the previous window's by no more than the noise explains (accelerations shown),
//   sum_i (x''_k,i - x''_k-1,i)^2 <= kLepski sigma^2 sum_i |w''_k,i - w''_k-1,i|^2,
// that is while the smoothing adds less bias than the noise it removes (the sums run over the
// samples away from the ends, every stride-th one of a long recording). At the ends and gaps the
// accelerations come from the window one shorter at order 4 at most: a one-sided fit's bias and
// variance grow faster with its length and order. sigma, each series' noise level, comes from
// the shortest window's residuals (Craven & Wahba 1979):
//   sigma^2 = sum_i (x_i - x^_i)^2 / (n - tr H),  tr H = sum_i h_ii,
// h_ii being the fit's own weight on x_i. The standard errors follow from the weights:
// se(x'_i) = sigma |w'_i|, se(x''_i) = sigma |w''_i| (white noise), widened by the squared bias
// the last accepted step showed beyond the noise: its mean over the samples, or the sample's own
// step where larger. One pass chooses (each window's weights once per
// sample, shared by every series), one estimates (the chosen windows' weights once per sample):
// linear in the length.
#pragma once

#include <vector>

#include "mb_kinematics/estimation/offline_estimator.h"

namespace mbk {

// The windows tried on the stamps t, shortest first.
std::vector<OfflineEstimator> auto_candidates(const std::vector<double>& t);

struct AutoEstimate {
  int series = 0;                           // m
  std::vector<double> first, second;        // [r * m + c]
  std::vector<double> first_se, second_se;  // [r * m + c], one standard error
  std::vector<int> valid;                   // [r * m + c], as DerivativeWeights::valid
  std::vector<double> noise;                // per series: sigma
  std::vector<int> choice;                  // per series: index in auto_candidates(t)
};

// m series sampled together at the increasing stamps t, stored x[r * ld + c]; each chooses its
// own windows (one for the velocities, one for the accelerations); choice: the latter.
void estimate_auto(const std::vector<double>& t, const double* x, int ld, int m, double max_gap,
                   AutoEstimate& out);

}  // namespace mbk
