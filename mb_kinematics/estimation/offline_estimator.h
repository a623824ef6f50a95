// Zero-phase (centred) derivative estimates for recorded data, where every sample is known in
// advance: at each sample, a least-squares polynomial through the samples on both sides of it
// (irregular stamps allowed), differentiated at the sample's own stamp. Near the recording's
// ends and at gaps longer than `max_gap` the window is shifted to stay on one side (a one-sided
// fit); a segment shorter than the window is fitted whole, with a lower order if it must.
// The weights depend on the stamps only, so one set serves every coordinate sampled together.
#pragma once

#include <string>
#include <vector>

namespace mbk {

struct OfflineEstimator {
  std::string name;           // as --estimator takes it, e.g. "centered_0.1s_3" or "centered_9_4"
  int window_samples = 0;     // > 0: the window holds this many samples (odd)
  double window_seconds = 0;  // > 0: the window spans this many seconds, centred on the sample,
                              // widened to hold order + 3 samples where the samples are sparse
  int order = 2;              // degree of the polynomial (2..5; auto's: up to 6)
  bool automatic = false;     // "auto": chosen per series (estimation/auto_estimator.h)
  bool butterworth = false;   // "butterworth:FC" (estimation/butterworth_estimator.h)
  double cutoff = 0;          // its FC, Hz; 0: "butterworth:auto" (Winter's residual analysis)
  // Estimated over whole series at once, with error bars: "auto" and "butterworth:...".
  bool whole_series() const { return automatic || butterworth; }
};

// "auto", "centered_<N>_<order>" (N samples, odd), "centered_<seconds>s_<order>",
// "butterworth:<FC Hz>" or "butterworth:auto"; throws std::invalid_argument naming the known forms.
OfflineEstimator make_offline_estimator(const std::string& name);
// The studied ones (work-precision report, doc/error_vs_runtime.md), the default first.
const std::vector<std::string>& offline_estimator_names();
const char* default_offline_estimator();

// Samples fitted by one window at most: a time window holding more (a high rate) takes every
// stride-th sample, the estimated one included, so the cost per sample does not grow with the
// rate.
constexpr int kMaxOfflineWindow = 41;

// How far one sample's estimate reaches, for computing a recording piece by piece
// (offline/offline_stream.h): the estimate at t_i reads, and where its window lies depends on,
// only the samples within `seconds` of t_i and the `samples` next ones beyond those on either
// side (and the gaps between them). An estimator that reaches every sample ("auto": it chooses
// its smoothing over the whole series) cannot say: offline_reach returns false.
struct OfflineReach {
  double seconds = 0;
  int samples = 0;
};
bool offline_reach(const OfflineEstimator& e, OfflineReach& reach);

// Weights of one sample's estimate: x'(t_i) = sum_j first[j] x[row(j)], likewise x''.
struct DerivativeWeights {
  int begin = 0, count = 0, stride = 1;
  int row(int j) const { return begin + j * stride; }
  int valid = 0;  // 0: none (a lone sample), 1: first derivative only, 2: both
  std::vector<double> first, second;
  std::vector<double> value;  // the fitted x(t_i) (the smoother's row; the automatic estimator)
};

// Index ranges [begin, end) of the runs of `t` (increasing) without a gap longer than max_gap
// (max_gap <= 0: no gaps); segment_of[i] is the run holding sample i. period > 0: the stamps lie
// on a uniform grid of that period (StampGrid::found, estimation/stamp_grid.h), so the weights
// take the offsets between them as whole periods (derivative_weights).
struct Segments {
  std::vector<int> begin, end, segment_of;
  double period = 0;
};
Segments find_segments(const std::vector<double>& t, double max_gap, double period = 0);

// The weights for sample i of the increasing stamps t (within its segment); e is not automatic.
// They are fitted in the offsets t_j - t_i: whole periods of segments.period where it is set,
// else whole nanoseconds where the stamps are (a bag's; to within their double rounding), else
// the doubles' differences. Each thread keeps the weights of the windows it computed last,
// found again by their order and offsets to the bit: on a grid, a window's weights are computed
// about once per thread, with the same results.
void derivative_weights(const OfflineEstimator& e, const std::vector<double>& t,
                        const Segments& segments, int i, DerivativeWeights& w);

// The estimates of n series sampled together and stored row by row (x[r * ld + c]: series c at
// sample r) at once: first[c] = sum_j w.first[j] x[w.row(j) * ld + c], likewise second with
// w.second unless it is nullptr. The same sums, in the same order, as one series at a time.
void apply_weights(const DerivativeWeights& w, const double* x, int ld, int n, double* first,
                   double* second);

// 5 x the median interval of t: what counts as a gap unless the user says otherwise.
double default_max_gap(const std::vector<double>& t);

// Both derivatives of x at every sample (convenience for studies and tests): `valid` per sample;
// an automatic e chooses its window for x, a Butterworth one filters the whole of x.
void estimate_offline(const OfflineEstimator& e, const std::vector<double>& t,
                      const std::vector<double>& x, double max_gap, std::vector<double>& first,
                      std::vector<double>& second, std::vector<int>& valid);

}  // namespace mbk
