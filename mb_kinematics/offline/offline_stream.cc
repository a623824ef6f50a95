#include "mb_kinematics/offline/offline_stream.h"

#include <algorithm>

namespace mbk {

namespace {

// Buffer rows [next, next + chunk) of the stamps t are ready when the buffer holds, beyond the
// first row more than reach.seconds after the last of them, reach.samples rows more (and one for
// rounding); returns their end, or next.
int ready_end(const std::vector<double>& t, int next, int chunk, const OfflineReach& reach) {
  const int i = next + chunk - 1;
  const int k =
      static_cast<int>(std::upper_bound(t.begin() + i, t.end(), t[i] + reach.seconds) - t.begin());
  return k + reach.samples + 1 < static_cast<int>(t.size()) ? i + 1 : next;
}

// The buffer rows before `next` that no row from next on reaches.
int forgettable(const std::vector<double>& t, int next, const OfflineReach& reach) {
  if (next >= static_cast<int>(t.size())) return 0;
  const int p = static_cast<int>(
      std::lower_bound(t.begin(), t.begin() + next, t[next] - reach.seconds) - t.begin());
  return std::max(0, p - reach.samples - 2);
}

template <typename T>
void drop_front(std::vector<T>& v, size_t count) {
  v.erase(v.begin(), v.begin() + count);
}

}  // namespace

RecordingSurvey::RecordingSurvey(int nq, bool keep_intervals, std::size_t interval_bins)
    : nq(nq),
      keep_intervals(keep_intervals),
      position_everywhere(nq, 1),
      position_somewhere(nq, 0),
      velocity_everywhere(nq, 1),
      intervals(interval_bins) {}

void RecordingSurvey::add(double t, const std::uint8_t* given) {
  add_stamp(t);
  ++rows;
  for (int c = 0; c < nq; ++c) {
    position_everywhere[c] = position_everywhere[c] && (given[c] & Recording::kPosition);
    position_somewhere[c] = position_somewhere[c] || (given[c] & Recording::kPosition);
    velocity_everywhere[c] = velocity_everywhere[c] && (given[c] & Recording::kVelocity);
  }
}

void RecordingSurvey::add_stamp(double t) {
  if (stamps_in_pass++ > 0 && keep_intervals) intervals.add(t - last_stamp);
  last_stamp = t;
}

bool RecordingSurvey::finish_pass() {
  stamps_in_pass = 0;
  return !keep_intervals || intervals.finish_pass();
}

// As default_max_gap: the interval at index n / 2 of the n intervals in increasing order.
double RecordingSurvey::default_max_gap() const {
  return rows < 2 || !keep_intervals ? 0 : 5 * intervals.median();
}

bool RecordingSurvey::streamable() const {
  for (int c = 0; c < nq; ++c)
    if (position_somewhere[c] && !position_everywhere[c]) return false;
  return true;
}

OfflineStream::OfflineStream(const Model& model, const OfflineEstimator& estimator,
                             const OfflineReach& reach, double max_gap, WholeRecording whole,
                             int threads, int chunk_rows, RowSink sink)
    : model_(model),
      estimator_(estimator),
      reach_(reach),
      max_gap_(max_gap),
      whole_(std::move(whole)),
      threads_(threads),
      chunk_rows_(std::max(1, chunk_rows)),
      sink_(std::move(sink)) {
  buffer_.nq = model.nq;
}

void OfflineStream::add(double t, const double* position, const double* velocity,
                        const std::uint8_t* given) {
  const int nq = buffer_.nq;
  buffer_.stamp.push_back(grid_.snap(t));
  if (grid_.moves) buffer_.recorded_stamp.push_back(t);
  buffer_.position.insert(buffer_.position.end(), position, position + nq);
  buffer_.velocity.insert(buffer_.velocity.end(), velocity, velocity + nq);
  buffer_.acceleration.insert(buffer_.acceleration.end(), nq, 0.0);
  buffer_.given.insert(buffer_.given.end(), given, given + nq);
  peak_rows_ = std::max(peak_rows_, buffer_.rows());
  if (buffer_.rows() - next_ >= chunk_rows_) {
    const int end = ready_end();
    if (end - next_ >= chunk_rows_) compute(end);
  }
}

int OfflineStream::ready_end() const {
  return mbk::ready_end(buffer_.stamp, next_, chunk_rows_, reach_);
}

void OfflineStream::compute(int end, bool last) {
  OfflineBatch batch(model_, buffer_, estimator_, max_gap_, nullptr, threads_, &whole_);
  batch.set_formatter(formatter_);
  batch.set_body_errors(body_errors_);
  const RowSeconds s = compute_rows(
      batch, model_, next_, end, sink_, [](int) {}, &rows_);
  seconds_.compute += s.compute, seconds_.use += s.use;
  if (hook_) hook_(batch.states(), buffer_, next_, end);
  if (estimator_.automatic) batch.states().append_errors(next_, end, columns_, threads_);
  if (estimator_.automatic && last) errors_ = batch.states().error_summary(&columns_);
  next_ = end;
  forget();
}

void OfflineStream::forget() {
  const int drop = forgettable(buffer_.stamp, next_, reach_);
  if (drop == 0) return;
  const size_t nq = buffer_.nq;
  drop_front(buffer_.stamp, drop);
  if (grid_.moves) drop_front(buffer_.recorded_stamp, drop);
  for (auto* v : {&buffer_.position, &buffer_.velocity, &buffer_.acceleration})
    drop_front(*v, drop * nq);
  drop_front(buffer_.given, drop * nq);
  next_ -= drop;
}

void OfflineStream::finish() {
  if (next_ < buffer_.rows()) compute(buffer_.rows(), true);
}

AutoChoosePass::AutoChoosePass(const Model& model, const RecordingSurvey& survey, double max_gap,
                               int chunk_rows, int threads)
    : nq_(survey.nq),
      max_gap_(max_gap),
      chunk_rows_(std::max(1, chunk_rows)),
      velocity_everywhere_(survey.velocity_everywhere),
      positions_(survey.default_max_gap() / 5, survey.rows, survey.nq, threads),
      reach_(positions_.reach()),
      rotations_(model, survey.default_max_gap() / 5) {
  for (int c = 0; c < nq_; ++c)
    if (survey.rows > 0 && survey.position_everywhere[c] && survey.velocity_everywhere[c])
      velocities_ =
          std::make_unique<AutoChooser>(survey.default_max_gap() / 5, survey.rows, nq_, threads);
}

void AutoChoosePass::add(double t, const double* position, const double* velocity) {
  t_.push_back(t);
  position_.insert(position_.end(), position, position + nq_);
  velocity_.insert(velocity_.end(), velocity, velocity + nq_);
  peak_rows_ = std::max(peak_rows_, static_cast<int>(t_.size()));
  if (static_cast<int>(t_.size()) - next_ >= chunk_rows_) {
    const int end = ready_end(t_, next_, chunk_rows_, reach_);
    if (end - next_ >= chunk_rows_) take(end);
  }
}

void AutoChoosePass::take(int end) {
  const Segments segments = find_segments(t_, max_gap_, grid_period(grid_));
  positions_.add(t_, segments, position_.data(), nq_, first_, next_, end);
  if (velocities_) velocities_->add(t_, segments, velocity_.data(), nq_, first_, next_, end);
  rotations_.add(t_, segments, position_.data(), nq_, next_, end);
  next_ = end;
  const int drop = forgettable(t_, next_, reach_);
  drop_front(t_, drop);
  drop_front(position_, static_cast<size_t>(drop) * nq_);
  drop_front(velocity_, static_cast<size_t>(drop) * nq_);
  next_ -= drop, first_ += drop;
}

WholeRecording AutoChoosePass::finish(OfflineReach& reach) {
  if (next_ < static_cast<int>(t_.size())) take(static_cast<int>(t_.size()));
  WholeRecording out{velocity_everywhere_,
                     std::make_shared<const AutoChoice>(
                         angles_first_chain(positions_.choice(), rotations_.joints())),
                     nullptr,
                     std::make_shared<const std::vector<Mat3<double>>>(rotations_.covariance())};
  reach = out.positions->reach();
  if (velocities_) {
    out.velocities = std::make_shared<const AutoChoice>(velocities_->choice());
    const OfflineReach of_velocities = out.velocities->reach();
    reach.seconds = std::max(reach.seconds, of_velocities.seconds);
    reach.samples = std::max(reach.samples, of_velocities.samples);
  }
  return out;
}

}  // namespace mbk
