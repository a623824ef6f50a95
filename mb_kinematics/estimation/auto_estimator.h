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
// variance grow faster with its length and order. Where the window is centred, the accelerations
// come from a second choice the same way among auto_centred_candidates (long windows at order 6,
// kept while their estimates moved by at most 1.5 times what the noise explains), their error
// bars' bias from each sample's step to the next window divided by how much faster that one's
// bias grows (bias_growth).
// sigma, each series' noise level, comes from the shortest window's residuals (Craven & Wahba
// 1979):
//   sigma^2 = sum_i (x_i - x^_i)^2 / (n - tr H),  tr H = sum_i h_ii,
// h_ii being the fit's own weight on x_i. The standard errors follow from the weights:
// se(x'_i) = sigma |w'_i|, se(x''_i) = sigma |w''_i| (white noise), widened by the squared bias
// the last accepted step showed beyond the noise: its mean over the samples, or the sample's own
// step where larger. One pass chooses (each window's weights once per
// sample, shared by every series), one estimates (the chosen windows' weights once per sample):
// linear in the length. Both also run a piece of the recording at a time (AutoChooser,
// estimate_chosen; offline/offline_stream.h), with the same results bit for bit.
#pragma once

#include <vector>

#include "mb_kinematics/estimation/offline_estimator.h"

namespace mbk {

// The windows tried on the stamps t, shortest first; on stamps of median interval dt.
std::vector<OfflineEstimator> auto_candidates(const std::vector<double>& t);
std::vector<OfflineEstimator> auto_candidates(double dt);
// The windows tried for the accelerations away from the ends and gaps: the same lengths, those
// of 61 median intervals and more at order 6 (for a centred window, the same accelerations as
// order 7): less noise and bias than order 4 at the length where both balance; then the longest
// two at order 4 again (slow motion: at most kMaxOfflineWindow samples fitted, a longer window
// at order 4 is less noisy than the longest at order 6). Not at the ends, where a one-sided
// fit's variance grows fast with its order.
std::vector<OfflineEstimator> auto_centred_candidates(double dt);
// How much more bias candidate k + 1's accelerations have than candidate k's, both centred, of
// one degree p: (L_k+1 / L_k)^q - 1, the bias growing as the window's length L to the power q =
// p + 1 - 2, one more where p is even (the next odd term of the signal's expansion has zero
// weight); 0 where k + 1 does not exist or has another degree.
double bias_growth(const std::vector<OfflineEstimator>& candidates, int k);

// What the choice pass found for m series: the windows tried, each series' noise level sigma and,
// per derivative d at [d - 1], its window (index in candidates) and the squared bias per sample
// its last accepted step showed beyond the noise; the same of the accelerations where the window
// of centred_candidates is centred (not shifted at an end or a gap).
struct AutoChoice {
  std::vector<OfflineEstimator> candidates, centred_candidates;
  std::vector<double> noise;
  std::vector<int> choice[2], centred_choice;  // centred_choice -1: the first chain's alone
  std::vector<double> bias2[2], centred_bias2;
  // How far the chosen windows reach, with the next window of each centred choice that
  // centred_accelerations steps to (the estimating pass's reach).
  OfflineReach reach() const;
};

// The choice pass over a recording of `rows` samples of median interval dt (default_max_gap / 5),
// given a piece at a time (offline/offline_stream.h) or whole: the same sums in the same order.
class AutoChooser {
 public:
  // threads: the series shared out among up to that many, 8 series each at least (each series'
  // sums its own, in the same order: the same bits on any count; each thread computes the windows'
  // weights itself); with too few series for that many, the selection samples shared out instead
  // (each sample's terms summed apart, then added to the sums in the samples' order: the same
  // bits).
  AutoChooser(double dt, long rows, int m, int threads = 1);
  // How far a selection sample's sums reach (the longest candidate's).
  OfflineReach reach() const;
  // Rows [from, to) of a piece of the recording whose row 0 is the recording's row `first`:
  // stamps t, their segments, series x[r * ld + c]; each such row's reach must lie in the piece
  // as it does in the recording (or the piece holds the recording's end there). In order.
  void add(const std::vector<double>& t, const Segments& segments, const double* x, int ld,
           long first, int from, int to);
  AutoChoice choice() const;

  // Per series: the shortest window's residuals' squares, its trace and the samples counted;
  // per candidate k >= 1, over the samples where both k and k - 1 are centred,
  // moved[k * m + c] = sum_i (x_k,i - x_k-1,i)^2, change[k] = sum_i |w_k,i - w_k-1,i|^2, count[k].
  struct Residuals {
    std::vector<double> rss;
    double trace = 0, count = 0;
  };
  struct Statistics {
    std::vector<double> moved, change, count;
  };

 private:
  struct Sums;  // the sums below, of the whole recording or of one selection sample
  void add_by_samples(const std::vector<double>& t, const Segments& segments, const double* x,
                      int ld, long first, int from, int to);

  std::vector<OfflineEstimator> candidates_, centred_;
  int stride_, m_, threads_;
  int sample_threads_;  // > 1: the selection samples shared out (add_by_samples)
  Residuals residuals_;
  Statistics stats_[2];       // per derivative d at [d - 1]
  Statistics centred_stats_;  // of centred_, the accelerations' (past the shared windows)
  size_t shared_ = 0;         // the windows candidates_ and centred_ begin with alike
};

// At sample i, the weights of candidate k (`w`), of the candidate before it (`shorter`, when
// has_shorter) and, where w is shifted (an end, a gap), of that one at order 4 at most (`end`,
// which the accelerations apply there: a one-sided fit's bias and variance grow faster with its
// length and order). Per derivative d at [d - 1]: |w|^2 and |w - shorter|^2; end_norm = |end''|.
struct AutoSampleWeights {
  DerivativeWeights w, shorter, end;
  bool shifted = false, has_shorter = false;
  // w is centred on the sample (not shifted); of load_centred: and so is `longer` where
  // bias_growth > 0 (its accelerations replace the first chain's there)
  bool centred = false;
  double norm2_w[2] = {0, 0}, step2[2] = {0, 0}, end_norm = 0;
  // The centred chain's candidate k (auto_centred_candidates, load_centred): where candidate
  // k + 1 has k's degree (bias_growth > 0) and is centred at the sample too, its weights
  // (`longer`, has_longer), |w'' - longer''|^2 and bias_growth(candidates, k).
  DerivativeWeights longer;
  bool has_longer = false;
  double step2_longer = 0, growth = 0;
  // known: candidate k - 1's weights at this sample when already computed (else nullptr).
  void load(const std::vector<OfflineEstimator>& candidates, const std::vector<double>& t,
            const Segments& segments, int i, int k, const DerivativeWeights* known = nullptr);
  // w, centred, norm2_w and the longer window's weights of the centred chain's candidate k.
  void load_centred(const std::vector<OfflineEstimator>& candidates, const std::vector<double>& t,
                    const Segments& segments, int i, int k);
  // The weights the estimate of derivative d applies.
  const DerivativeWeights& used(int d) const { return d == 2 && shifted ? end : w; }
};

struct AutoEstimate {
  int series = 0;                           // m
  std::vector<double> first, second;        // [r * m + c]
  std::vector<double> first_se, second_se;  // [r * m + c], one standard error
  std::vector<int> valid;                   // [r * m + c], as DerivativeWeights::valid
  std::vector<double> noise;                // per series: sigma
  std::vector<int> choice;                  // per series: index in auto_candidates(t)
  std::vector<double> cutoff;  // per series: "butterworth"'s FC, Hz (estimation/butterworth_estimator.h)
};

// m series sampled together at the increasing stamps t, stored x[r * ld + c]; each chooses its
// own windows (one for the velocities, one for the accelerations); choice: the latter.
// threads: the choice's and the estimating pass's (AutoChooser, estimate_chosen).
void estimate_auto(const std::vector<double>& t, const double* x, int ld, int m, double max_gap,
                   AutoEstimate& out, int threads = 1);
// The estimating pass with a choice made before (AutoChooser), on the whole recording or a piece
// of it (each row's estimate is the whole recording's where the longest chosen window's reach lies
// in the piece as in the recording), of stamps t and their segments. Its samples shared out among
// up to `threads` threads (a sample's estimates are its own: the same bits on any count).
void estimate_chosen(const AutoChoice& choice, const std::vector<double>& t,
                     const Segments& segments, const double* x, int ld, AutoEstimate& out,
                     int threads = 1);

}  // namespace mbk
