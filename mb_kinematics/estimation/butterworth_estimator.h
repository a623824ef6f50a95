// The zero-lag Butterworth filter as biomechanics applies it (Winter, Biomechanics and Motor
// Control of Human Movement, 4th ed., ch. 2): a 2nd-order low-pass run forward then backward,
// its cutoff corrected for the two passes (C = (2^(1/n) - 1)^(1/4), n = 2 passes: the filter of
// each pass is designed at FC / C = 1.247 FC, so that the two together are 3 dB down at FC), and
// the velocities and accelerations of the filtered series by 5-point differences (the derivatives
// of the quartic through 5 filtered samples: central inside a segment, one-sided at its ends;
// error O(h^4)). "butterworth:FC" filters at
// FC Hz; "butterworth:auto" chooses FC per series by Winter's residual analysis: the residual
// R(f) = rms(x - filtered at f) against f, a straight line (the noise line) fitted to its
// high-frequency end (0.4 to 0.7 of C x Nyquist) and extrapolated to 0 Hz, FC where R(FC) equals
// that intercept. Each segment between gaps is filtered on its own, its samples taken as evenly
// spaced at the recording's median interval h (by the filter and the differences: with jittered
// stamps, each estimate is of the time on that grid, its stamp's error within x'' times the
// jitter), both ends padded by odd reflection (2 x_0 - x_k,
// k = 1..p; p = 12 / (1 - r) samples of FC's filter, r its poles' radius, so that the passes'
// starting transients decay by e^-12 before the data; at least 9, at most n - 1) and each pass
// started from its steady state for its first value: scipy.signal.filtfilt(b, a, x,
// padtype="odd", padlen=p).
// Error bars as for "auto" (estimation/auto_estimator.h): sigma^2 = RSS / sum(1 - 2 h_ii +
// |h_i|^2) of the filter at the noise line's top cutoff, se = sigma |w| (w: the estimate's
// weights over the samples: filter then difference, exact at the ends too), widened by the
// squared bias the step to twice the cutoff (0.9 C x Nyquist at most) showed beyond the noise
// (its mean over the samples away from the ends, or the sample's own where larger).
#pragma once

#include <vector>

#include "mb_kinematics/estimation/auto_estimator.h"
#include "mb_kinematics/estimation/offline_estimator.h"

namespace mbk {

// Winter's correction of the cutoff for `passes` passes of a 2nd-order filter.
double butterworth_correction(int passes = 2);

// One pass: a 2nd-order Butterworth low-pass at `cutoff` Hz for samples at `rate` Hz (bilinear
// transform with pre-warping: scipy.signal.butter(2, cutoff / (rate / 2))), in transposed direct
// form II (y = b0 x + z0, z0 = b1 x - a1 y + z1, z1 = b2 x - a2 y), zi its state after a long
// run of ones (scipy.signal.lfilter_zi). Throws std::invalid_argument unless 0 < cutoff < rate / 2.
struct Butterworth2 {
  double b[3], a[3];
  double zi[2];
};
Butterworth2 butterworth_lowpass(double cutoff, double rate);

// The samples padded at each end by odd reflection for the filter f: 12 / (1 - r), at least 9.
int butterworth_padding(const Butterworth2& f);
// Forward then backward over x[0..n), padded by min(pad, n - 1) samples (above); y may be x.
// scratch: reused.
void filtfilt(const Butterworth2& f, const double* x, int n, double* y,
              std::vector<double>& scratch, int pad);

// Winter's residual analysis of one series (its segments between gaps), samples at `rate` Hz: the
// chosen cutoff, the noise line's intercept, and the cutoff range searched.
struct ResidualChoice {
  double cutoff = 0, intercept = 0, lowest = 0, highest = 0;
};
ResidualChoice residual_cutoff(const std::vector<double>& x, const Segments& segments, double rate);

// The estimates and error bars of m series sampled together at the increasing stamps t, stored
// x[r * ld + c]; e.butterworth. out.cutoff: each series' FC.
void estimate_butterworth(const OfflineEstimator& e, const std::vector<double>& t, const double* x,
                          int ld, int m, double max_gap, AutoEstimate& out, int threads = 1);

// |w|^2 of each sample's velocity and acceleration estimate from a segment at the stamps t filtered
// at `cutoff` Hz (w: the estimate's weights over the samples; sigma |w| is its error bar's noise
// part): exact near the ends, from the responses' autocorrelations in between.
void butterworth_weight_norms(double cutoff, double rate, const std::vector<double>& t,
                              std::vector<double>& first, std::vector<double>& second);

// The estimators with error bars over whole series ("auto", "butterworth:..."): estimate_auto or
// estimate_butterworth.
void estimate_with_errors(const OfflineEstimator& e, const std::vector<double>& t, const double* x,
                          int ld, int m, double max_gap, AutoEstimate& out, int threads = 1);

}  // namespace mbk
