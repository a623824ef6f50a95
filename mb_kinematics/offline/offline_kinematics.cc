#include "mb_kinematics/offline/offline_kinematics.h"

#include <algorithm>
#include <cmath>

#include "mb_kinematics/core/body_errors.h"
#include "mb_kinematics/core/split_runs.h"
#include "mb_kinematics/estimation/butterworth_estimator.h"

namespace mbk {

OfflineStates::OfflineStates(const Model& model, const Recording& recording,
                             const OfflineEstimator& estimator, double max_gap,
                             const WholeRecording* whole, int threads)
    : model_(model),
      rec_(recording),
      estimator_(estimator),
      max_gap_(max_gap > 0 ? max_gap : default_max_gap(recording.stamp)),
      velocity_everywhere_(model.nq, 1),
      rule_until_(model.nq, 0),
      first_(Eigen::VectorXd::Zero(model.nq)),
      second_(Eigen::VectorXd::Zero(model.nq)),
      velocity_first_(Eigen::VectorXd::Zero(model.nq)) {
  if (recording.nq != model.nq || recording.given.size() != recording.stamp.size() * model.nq)
    throw std::invalid_argument("a recording of another model: " + std::to_string(recording.nq) +
                                " coordinates, the model has " + std::to_string(model.nq));
  std::vector<char> everywhere(model.nq, 1);
  const int nq = model.nq;
  for (int r = 0; r < rec_.rows(); ++r)
    for (int c = 0; c < nq; ++c) {
      const std::uint8_t g = rec_.given[r * nq + c];
      everywhere[c] = everywhere[c] && (g & Recording::kPosition);
      velocity_everywhere_[c] = velocity_everywhere_[c] && (g & Recording::kVelocity);
    }
  if (whole) {
    velocity_everywhere_ = whole->velocity_everywhere;
    positions_choice_ = whole->positions, velocities_choice_ = whole->velocities;
    whole_noise_ = whole->rotation_noise;
  }
  for (const Mimic& m : model.mimics) {  // the rule places a mimic until it is recorded
    int& r = rule_until_[m.coordinate];
    while (r < rec_.rows() && !(rec_.given[r * nq + m.coordinate] & Recording::kPosition)) ++r;
  }
  for (int c = 0; c < nq; ++c) {
    if (rule_until_[c] == rec_.rows() && rec_.rows() > 0) continue;  // a mimic never recorded
    if (everywhere[c]) {
      full_.push_back(c);
      continue;
    }
    partial_.push_back(c);
    Series s;
    for (int r = 0; r < rec_.rows(); ++r)
      if (rec_.given[r * nq + c] & Recording::kPosition)
        s.t.push_back(rec_.stamp[r]), s.row.push_back(r);
    s.segments = find_segments(s.t, max_gap > 0 ? max_gap : default_max_gap(s.t));
    series_.push_back(std::move(s));
  }
  segments_ = find_segments(rec_.stamp, max_gap_, grid_period(rec_.grid));
  for (int c : full_)
    any_velocity_everywhere_ = any_velocity_everywhere_ || velocity_everywhere_[c];
  constexpr std::uint8_t kBoth = Recording::kVelocity | Recording::kAcceleration;
  positions_only_.assign(rec_.rows(), !full_.empty());
  derivatives_given_.assign(rec_.rows(), !full_.empty());
  for (int r = 0; r < rec_.rows(); ++r)
    for (int c : full_) {
      const std::uint8_t g = rec_.given[r * nq + c] & kBoth;
      positions_only_[r] = positions_only_[r] && g == 0;
      derivatives_given_[r] = derivatives_given_[r] && g == kBoth;
    }
  if (estimator_.whole_series()) fit_automatic(threads);
}

// "auto": every row's estimates at once, each coordinate choosing its own smoothing (of its
// given velocities too where it has them everywhere); a partial coordinate over its own samples.
void OfflineStates::fit_automatic(int threads) {
  const int nq = rec_.nq;
  auto fit = [&](const std::vector<double>& x, const AutoChoice* choice) {
    auto a = std::make_shared<AutoEstimate>();
    if (choice)
      estimate_chosen(*choice, rec_.stamp, segments_, x.data(), nq, *a, threads);
    else
      estimate_with_errors(estimator_, rec_.stamp, x.data(), nq, nq, max_gap_, *a, threads);
    return a;
  };
  if (!full_.empty() && estimator_.automatic && !positions_choice_) {  // kept for the error bars
    AutoChooser chooser(default_max_gap(rec_.stamp) / 5, rec_.rows(), nq, threads);
    chooser.add(rec_.stamp, segments_, rec_.position.data(), nq, 0, 0, rec_.rows());
    positions_choice_ = std::make_shared<const AutoChoice>(
        angles_first_chain(chooser.choice(), angle_joints(model_)));
  }
  if (!full_.empty()) positions_fit_ = fit(rec_.position, positions_choice_.get());
  find_rotations();
  if (any_velocity_everywhere_) velocities_fit_ = fit(rec_.velocity, velocities_choice_.get());
  for (size_t i = 0; i < partial_.size(); ++i) {
    Series& s = series_[i];
    const int c = partial_[i];
    const size_t n = s.row.size();
    std::vector<double> x(2 * n);  // [k * 2]: position, [k * 2 + 1]: velocity
    for (size_t k = 0; k < n; ++k)
      x[2 * k] = rec_.position[s.row[k] * nq + c], x[2 * k + 1] = rec_.velocity[s.row[k] * nq + c];
    auto a = std::make_shared<AutoEstimate>();
    estimate_with_errors(estimator_, s.t, x.data(), 2, velocity_everywhere_[c] ? 2 : 1,
                         max_gap_ > 0 ? max_gap_ : default_max_gap(s.t), *a);
    s.fit = std::move(a);
  }
}

// The joints on angles whose three angles come from "auto" over the positions in every row, and
// their rotation noise (the whole recording's, or this one's).
void OfflineStates::find_rotations() {
  if (!estimator_.automatic || !positions_fit_) return;
  const int nq = rec_.nq;
  std::vector<char> full(nq, 0);
  for (int c : full_) full[c] = !velocity_everywhere_[c];
  std::vector<Mat3<double>> noise;
  if (whole_noise_) {
    noise = *whole_noise_;
  } else {
    RotationNoise sum(model_, default_max_gap(rec_.stamp) / 5);
    sum.add(rec_.stamp, segments_, rec_.position.data(), nq, 0, rec_.rows());
    noise = sum.covariance();
  }
  const std::vector<AngleJoint> all = angle_joints(model_);
  for (size_t g = 0; g < all.size() && g < noise.size(); ++g) {
    const int c = all[g].coordinate;
    if (full[c] && full[c + 1] && full[c + 2])
      rotations_.push_back(all[g]), rotation_noise_.push_back(noise[g]);
  }
  weights_row_.assign(positions_choice_->candidates.size(), -1);
  // A window's rows at most, and about 20 MB per worker however many joints.
  const size_t rows = std::min<size_t>(1024, std::max(16, rec_.rows()));
  noise_rows_ =
      std::clamp<size_t>(kAngleNoiseEntries / std::max<size_t>(1, rotations_.size()), 16, rows);
  noise_at_.resize(rotations_.size() * noise_rows_);
  noise_row_.assign(rotations_.size() * noise_rows_, -1);
  window_weights_.resize(positions_choice_->candidates.size());
}

namespace {

// The median of column c of v (v[k * m + c]), as MedianHistogram's.
double column_median(const std::vector<double>& v, int m, int c) {
  MedianHistogram column;
  for (size_t at = c; at < v.size(); at += m) column.add(v[at]);
  return column.median();
}

}  // namespace

std::size_t ErrorColumns::bytes() const {
  std::size_t sum = 0;
  for (const auto* columns : {&velocity, &acceleration})
    for (const MedianHistogram& h : *columns) sum += h.bytes();
  return sum;
}

void OfflineStates::append_errors(int begin, int end, ErrorColumns& out, int threads) const {
  if (!positions_fit_) return;
  out.velocity.resize(full_.size()), out.acceleration.resize(full_.size());
  const int nq = rec_.nq;
  split_runs(full_.size(), std::max(1, threads), [&](size_t, size_t first, size_t last) {
    for (size_t k = first; k < last; ++k) {
      const int c = full_[k];
      // Accelerations from given velocities: their first derivative's error bar.
      const AutoEstimate* v = velocity_everywhere_[c] ? velocities_fit_.get() : nullptr;
      for (int r = begin; r < end; ++r) {
        const size_t at = static_cast<size_t>(r) * nq + c;
        out.velocity[k].add(positions_fit_->first_se[at]);
        out.acceleration[k].add(v ? v->first_se[at] : positions_fit_->second_se[at]);
      }
    }
  });
}

std::vector<CoordinateError> OfflineStates::error_summary(const ErrorColumns* whole) const {
  std::vector<CoordinateError> out;
  ErrorColumns mine;
  if (!whole) append_errors(0, rec_.rows(), mine);
  const ErrorColumns& columns = whole ? *whole : mine;
  if (positions_fit_)
    for (size_t k = 0; k < full_.size(); ++k)
      out.push_back({model_.coordinate_names[full_[k]], positions_fit_->noise[full_[k]],
                     columns.velocity[k].median(), columns.acceleration[k].median()});
  for (size_t i = 0; i < partial_.size(); ++i)
    if (series_[i].fit) {
      const AutoEstimate& a = *series_[i].fit;
      const int m = a.series;  // accelerations from given velocities: column 1's velocity
      out.push_back({model_.coordinate_names[partial_[i]], a.noise[0],
                     column_median(a.first_se, m, 0),
                     column_median(velocity_everywhere_[partial_[i]] ? a.first_se : a.second_se, m,
                                   velocity_everywhere_[partial_[i]] ? 1 : 0)});
    }
  return out;
}

bool OfflineStates::coordinate_errors(int r, double* velocity_se, double* acceleration_se) const {
  if (!estimator_.whole_series()) return false;
  const int nq = rec_.nq;
  for (size_t i = 0; i < partial_.size(); ++i)
    if (r >= rule_until_[partial_[i]])  // else a mimic placed by its rule: exact
      series_errors(i, r, velocity_se[partial_[i]], acceleration_se[partial_[i]]);
  if (!positions_fit_) return true;
  for (int c : full_) {  // what the sample gives is exact
    const size_t at = static_cast<size_t>(r) * nq + c;
    const std::uint8_t given = rec_.given[at];
    const bool velocity = velocity_everywhere_[c] && velocities_fit_;
    velocity_se[c] =
        velocity || (given & Recording::kVelocity) ? 0.0 : positions_fit_->first_se[at];
    acceleration_se[c] = given & Recording::kAcceleration ? 0.0
                         : velocity                       ? velocities_fit_->first_se[at]
                                                          : positions_fit_->second_se[at];
  }
  return true;
}

// Partial coordinate i's error bars at row r: those of its last sample up to r, whose
// derivatives hold until its next (estimate_series).
void OfflineStates::series_errors(size_t i, int r, double& velocity_se,
                                  double& acceleration_se) const {
  const Series& s = series_[i];
  const int c = partial_[i];
  const auto next = std::upper_bound(s.row.begin(), s.row.end(), r);
  velocity_se = acceleration_se = 0;
  if (next == s.row.begin() || !s.fit) return;
  const AutoEstimate& a = *s.fit;
  const size_t entry = static_cast<size_t>(next - s.row.begin()) - 1, at = entry * a.series;
  const std::uint8_t given = rec_.given[static_cast<size_t>(s.row[entry]) * rec_.nq + c];
  if (!(given & Recording::kVelocity)) velocity_se = a.first_se[at];
  if (!(given & Recording::kAcceleration))
    acceleration_se = velocity_everywhere_[c] ? a.first_se[at + 1] : a.second_se[at];
}

bool OfflineStates::body_errors(int r, const JointState<double>& state, const Data<double>& data,
                                std::vector<Vec3<double>>& alpha_se,
                                std::vector<Vec3<double>>& acceleration_se) {
  if (!estimator_.whole_series() || model_.speeds != SpeedKind::kCoordinateDerivatives) return false;
  if (!scratch_.pv) {
    scratch_.pv = std::make_unique<PartialVelocities<double>>(model_, kStreamed);
    scratch_.data = std::make_unique<Data<double>>(model_);
    speed_se_.setZero(rec_.nq), speed_dot_se_.setZero(rec_.nq);
  }
  coordinate_errors(r, speed_se_.data(), speed_dot_se_.data());  // y = q': speed c is q_c'
  const bool rotations = !rotations_.empty() && positions_only_[r];
  if (rotations)  // carried as rotations below
    for (const AngleJoint& g : rotations_)
      for (int a = 0; a < 3; ++a) speed_se_[g.coordinate + a] = speed_dot_se_[g.coordinate + a] = 0;
  body_acceleration_errors(model_, state, *scratch_.pv, *scratch_.data, speed_se_.data(),
                           speed_dot_se_.data(), alpha_se, acceleration_se);
  if (!rotations) return true;
  alpha_var_.resize(alpha_se.size()), acceleration_var_.resize(acceleration_se.size());
  for (size_t k = 0; k < alpha_se.size(); ++k)
    alpha_var_[k] = alpha_se[k].cwiseAbs2(), acceleration_var_[k] = acceleration_se[k].cwiseAbs2();
  for (size_t g = 0; g < rotations_.size(); ++g) {
    const AngleJoint& j = rotations_[g];
    const Mat9 l = angle_error_map(
        model_.bodies[j.body].joint, state.position.data() + j.coordinate,
        state.velocity.data() + j.coordinate, state.acceleration.data() + j.coordinate);
    const Mat9 cov = l * angle_covariance(g, r) * l.transpose();
    add_joint_rotation_variance(model_, data, j.body, cov, alpha_var_, acceleration_var_, subtree_);
  }
  for (size_t k = 0; k < alpha_se.size(); ++k)
    alpha_se[k] = alpha_var_[k].cwiseSqrt(), acceleration_se[k] = acceleration_var_[k].cwiseSqrt();
  return true;
}

const AutoSampleWeights& OfflineStates::weights_at(int r, int k) {
  if (weights_row_[k] != r)
    window_weights_[k].load(positions_choice_->candidates, rec_.stamp, segments_, r, k),
        weights_row_[k] = r;
  return window_weights_[k];
}

// Joint g's angles' noise at row j, F_j = E_j^-1 noise E_j^-T (at the lock itself, E singular,
// the angles' own noise levels, apart), kept for the last noise_rows_ rows (a cache: any size
// gives the same values).
const Mat3<double>& OfflineStates::angle_noise(size_t g, int j) {
  const size_t at = g * noise_rows_ + static_cast<size_t>(j) % noise_rows_;
  if (noise_row_[at] == j) return noise_at_[at];
  const AngleJoint& joint = rotations_[g];
  const Mat3<double> e = angle_rate_matrix(model_.bodies[joint.body].joint,
                                           rec_.position.data() + j * rec_.nq + joint.coordinate);
  Mat3<double>& f = noise_at_[at];
  if (std::abs(e.determinant()) > 1e-12) {
    const Mat3<double> e_inv = e.inverse();
    f = e_inv * rotation_noise_[g] * e_inv.transpose();
  } else {
    f.setZero();
    for (int a = 0; a < 3; ++a) f(a, a) = std::pow(positions_fit_->noise[joint.coordinate + a], 2);
  }
  noise_row_[at] = j;
  return f;
}

// The covariance of the errors (dq, dq', dq'') of a joint's three angles at row r (slots
// 3 d + a: derivative d of angle a), with rotation noise `noise` (doc/method.md 11): at each
// sample j the angles' noise is F_j = E_j^-1 noise E_j^-T (E_j: core/rotation_errors.h at its
// angles), and the derivatives are sums of the samples with the weights "auto" applied, so
//   cov(slot s, slot s') = sum_j u_s,j u_s',j F_j[a, a']
// (u: 1 at row r for the angles themselves). Plus each derivative's bias (auto_estimator.h: its
// squared standard error beyond the noise, per angle) as one vector along the step from the
// shorter window's estimates: the bias of angles turning together is shared, not independent.
Mat9 OfflineStates::angle_covariance(size_t g, int r) {
  const AngleJoint& joint = rotations_[g];
  const int nq = rec_.nq;
  entries_.clear();
  for (int a = 0; a < 3; ++a) entries_.push_back({r, a, 1.0});
  Vec3<double> bias[2];
  for (int d = 1; d <= 2; ++d)
    for (int a = 0; a < 3; ++a) {
      const int c = joint.coordinate + a;
      const AutoSampleWeights& s = weights_at(r, positions_choice_->choice[d - 1][c]);
      const DerivativeWeights& used = s.used(d);
      const std::vector<double>& u = d == 1 ? used.first : used.second;
      double norm2 = 0, step = 0;
      for (int j = 0; j < used.count; ++j)
        entries_.push_back({used.row(j), 3 * d + a, u[j]}), norm2 += u[j] * u[j];
      if (s.has_shorter) {
        const std::vector<double>&w = d == 1 ? s.w.first : s.w.second,
              &v = d == 1 ? s.shorter.first : s.shorter.second;
        for (int j = 0; j < s.w.count; ++j) step += w[j] * rec_.position[s.w.row(j) * nq + c];
        for (int j = 0; j < s.shorter.count; ++j)
          step -= v[j] * rec_.position[s.shorter.row(j) * nq + c];
      }
      const size_t at = static_cast<size_t>(r) * nq + c;
      const double se = d == 1 ? positions_fit_->first_se[at] : positions_fit_->second_se[at];
      const double sigma = positions_fit_->noise[c];
      bias[d - 1][a] =
          std::copysign(std::sqrt(std::max(0.0, se * se - sigma * sigma * norm2)), step);
    }
  std::sort(entries_.begin(), entries_.end(),
            [](const Entry& x, const Entry& y) { return x.row < y.row; });
  Mat9 cov = Mat9::Zero();
  for (size_t i = 0; i < entries_.size();) {
    size_t end = i;
    while (end < entries_.size() && entries_[end].row == entries_[i].row) ++end;
    const Mat3<double>& f = angle_noise(g, entries_[i].row);
    for (size_t x = i; x < end; ++x)
      for (size_t y = i; y < end; ++y)
        cov(entries_[x].slot, entries_[y].slot) +=
            entries_[x].weight * entries_[y].weight * f(entries_[x].slot % 3, entries_[y].slot % 3);
    i = end;
  }
  for (int d = 1; d <= 2; ++d)
    cov.block<3, 3>(3 * d, 3 * d) += bias[d - 1] * bias[d - 1].transpose();
  return cov;
}

// "auto": full_'s derivatives at row r from the fits.
void OfflineStates::load_automatic(int r) {
  const int nq = rec_.nq;
  fit_valid_ = 2;
  for (int c : full_) {
    const size_t at = static_cast<size_t>(r) * nq + c;
    first_[c] = positions_fit_->first[at];
    second_[c] = positions_fit_->second[at];
    fit_valid_ = std::min(fit_valid_, positions_fit_->valid[at]);
    if (velocities_fit_) velocity_first_[c] = velocities_fit_->first[at];
  }
}

// x'(t) and x''(t) of coordinate c from the weights (over rows, or over a series' rows);
// with `velocity`, the acceleration is the first derivative of the given velocities.
void OfflineStates::derivatives(const DerivativeWeights& w, const std::vector<int>* rows, int c,
                                bool velocity, double& first, double& second) const {
  const int nq = rec_.nq;
  first = second = 0;
  for (int j = 0; j < w.count; ++j) {
    const int r = rows ? (*rows)[w.row(j)] : w.row(j);
    first += w.first[j] * rec_.position[r * nq + c];
    second +=
        velocity ? w.first[j] * rec_.velocity[r * nq + c] : w.second[j] * rec_.position[r * nq + c];
  }
}

// The coordinates of full_ at row r; valid drops to 0 where the fit lacks a needed derivative.
void OfflineStates::fill_full(int r, JointState<double>& state, int& valid) const {
  const int nq = rec_.nq;
  const std::uint8_t* given = rec_.given.data() + r * nq;
  if (positions_only_[r]) {  // every coordinate of full_ from the fit (the others are set later)
    state.position = Eigen::Map<const Eigen::VectorXd>(rec_.position.data() + r * nq, nq);
    state.velocity = first_;
    state.acceleration = second_;
    if (fit_valid_ < 2) valid = 0;
    return;
  }
  if (derivatives_given_[r]) {  // every coordinate of full_ as recorded (the others set later)
    state.position = Eigen::Map<const Eigen::VectorXd>(rec_.position.data() + r * nq, nq);
    state.velocity = Eigen::Map<const Eigen::VectorXd>(rec_.velocity.data() + r * nq, nq);
    state.acceleration = Eigen::Map<const Eigen::VectorXd>(rec_.acceleration.data() + r * nq, nq);
    return;
  }
  for (int c : full_) {
    state.position[c] = rec_.position[r * nq + c];
    state.velocity[c] = given[c] & Recording::kVelocity ? rec_.velocity[r * nq + c] : first_[c];
    state.acceleration[c] = given[c] & Recording::kAcceleration ? rec_.acceleration[r * nq + c]
                            : velocity_everywhere_[c] ? velocity_first_[c]  // from given v
                                                      : second_[c];
    // The derivative order this coordinate needs from the fit here.
    const int need =
        std::max(given[c] & Recording::kVelocity ? 0 : 1, given[c] & Recording::kAcceleration ? 0
                                                          : velocity_everywhere_[c]           ? 1
                                                                                              : 2);
    if (need > fit_valid_) valid = 0;
  }
}

// The derivatives of partial_[i]'s coordinate at its own sample `entry`, held until its next.
void OfflineStates::estimate_series(size_t i, size_t entry) {
  const int c = partial_[i];
  Series& s = series_[i];
  if (s.fit) {
    const AutoEstimate& a = *s.fit;
    const size_t at = entry * a.series;
    s.velocity = a.first[at];
    s.acceleration = velocity_everywhere_[c] ? a.first[at + 1] : a.second[at];
    s.valid = velocity_everywhere_[c] ? std::min(a.valid[at], a.valid[at + 1]) : a.valid[at];
  } else {
    DerivativeWeights& w = series_weights_;
    derivative_weights(estimator_, s.t, s.segments, static_cast<int>(entry), w);
    derivatives(w, &s.row, c, velocity_everywhere_[c], s.velocity, s.acceleration);
    s.valid = w.valid;
  }
  const int r = s.row[entry];
  const std::uint8_t g = rec_.given[r * rec_.nq + c];
  if (g & Recording::kVelocity) s.velocity = rec_.velocity[r * rec_.nq + c];
  if (g & Recording::kAcceleration)
    s.acceleration = rec_.acceleration[r * rec_.nq + c], s.valid = 2;
}

std::string OfflineStates::state_at(int r, JointState<double>& state) {
  const int nq = rec_.nq;
  // Does some coordinate of full_ lack a derivative here?
  const bool estimate = !full_.empty() && !derivatives_given_[r];
  int valid = 2;
  if (estimate && positions_fit_) {
    load_automatic(r);
  } else if (estimate) {
    derivative_weights(estimator_, rec_.stamp, segments_, r, weights_);
    fit_valid_ = weights_.valid;
    // One pass over the window's rows for all coordinates (positions, and given velocities).
    apply_weights(weights_, rec_.position.data(), nq, nq, first_.data(), second_.data());
    if (any_velocity_everywhere_)
      apply_weights(weights_, rec_.velocity.data(), nq, nq, velocity_first_.data(), nullptr);
  }
  fill_full(r, state, valid);
  for (size_t i = 0; i < partial_.size(); ++i) {
    const int c = partial_[i];
    Series& s = series_[i];
    // Rows skipped since the last call (a worker starting mid-recording): the last sample before
    // r is the one whose values hold.
    size_t k = s.next;
    while (k < s.row.size() && s.row[k] < r) ++k;
    if (k > s.next) estimate_series(i, k - 1);
    s.next = k;
    if (s.next < s.row.size() && s.row[s.next] == r) estimate_series(i, s.next++);
    // else the last sample's values hold
    if (r < rule_until_[c]) continue;  // a mimic not yet recorded: its rule, below
    state.position[c] = rec_.position[r * nq + c];
    state.velocity[c] = s.velocity;
    state.acceleration[c] = s.acceleration;
    valid = std::min(valid, s.valid);
  }
  // A recorded mimic value wins over the rule from its first sample on (as the node); in order:
  // a mimic of a mimic reads the result.
  for (const Mimic& m : model_.mimics)
    if (r < rule_until_[m.coordinate]) apply_mimic(m, state);
  if (valid < 2)
    return "too few samples around it for derivatives (a run of " + std::to_string(weights_.count) +
           " between gaps longer than " + std::to_string(max_gap_) + " s)";
  return "";
}

}  // namespace mbk
