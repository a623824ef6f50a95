#include "mb_kinematics/offline/offline_stream.h"

#include <algorithm>

namespace mbk {

RecordingSurvey::RecordingSurvey(int nq, bool keep_intervals)
    : nq(nq),
      keep_intervals(keep_intervals),
      position_everywhere(nq, 1),
      position_somewhere(nq, 0),
      velocity_everywhere(nq, 1) {}

void RecordingSurvey::add(double t, const std::uint8_t* given) {
  if (rows > 0 && keep_intervals) ++intervals[t - last_stamp];
  last_stamp = t;
  ++rows;
  for (int c = 0; c < nq; ++c) {
    position_everywhere[c] = position_everywhere[c] && (given[c] & Recording::kPosition);
    position_somewhere[c] = position_somewhere[c] || (given[c] & Recording::kPosition);
    velocity_everywhere[c] = velocity_everywhere[c] && (given[c] & Recording::kVelocity);
  }
}

// As default_max_gap: the interval at index n / 2 of the n intervals in increasing order.
double RecordingSurvey::default_max_gap() const {
  if (rows < 2) return 0;
  long at = (rows - 1) / 2;
  for (const auto& [interval, count] : intervals) {
    if (at < count) return 5 * interval;
    at -= count;
  }
  return 0;  // not reached
}

bool RecordingSurvey::streamable() const {
  for (int c = 0; c < nq; ++c)
    if (position_somewhere[c] && !position_everywhere[c]) return false;
  return true;
}

OfflineStream::OfflineStream(const Model& model, const OfflineEstimator& estimator,
                             const OfflineReach& reach, double max_gap,
                             std::vector<char> velocity_everywhere, int threads, int chunk_rows,
                             RowSink sink)
    : model_(model),
      estimator_(estimator),
      reach_(reach),
      max_gap_(max_gap),
      velocity_everywhere_(std::move(velocity_everywhere)),
      threads_(threads),
      chunk_rows_(std::max(1, chunk_rows)),
      sink_(std::move(sink)) {
  buffer_.nq = model.nq;
}

void OfflineStream::add(double t, const double* position, const double* velocity,
                        const std::uint8_t* given) {
  const int nq = buffer_.nq;
  buffer_.stamp.push_back(t);
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

// Row i is ready when the buffer holds, beyond the first row more than reach.seconds after it,
// reach.samples rows more (and one for rounding).
int OfflineStream::ready_end() const {
  const std::vector<double>& t = buffer_.stamp;
  const int i = next_ + chunk_rows_ - 1;
  const int k =
      static_cast<int>(std::upper_bound(t.begin() + i, t.end(), t[i] + reach_.seconds) - t.begin());
  return k + reach_.samples + 1 < buffer_.rows() ? i + 1 : next_;
}

void OfflineStream::compute(int end) {
  OfflineBatch batch(model_, buffer_, estimator_, max_gap_, nullptr, threads_,
                     &velocity_everywhere_);
  batch.set_formatter(formatter_);
  const RowSeconds s = compute_rows(batch, model_, next_, end, sink_, [](int) {});
  seconds_.compute += s.compute, seconds_.use += s.use;
  next_ = end;
  forget();
}

void OfflineStream::forget() {
  if (next_ >= buffer_.rows()) return;
  const std::vector<double>& t = buffer_.stamp;
  const int p = static_cast<int>(
      std::lower_bound(t.begin(), t.begin() + next_, t[next_] - reach_.seconds) - t.begin());
  const int drop = std::max(0, p - reach_.samples - 2);
  if (drop == 0) return;
  const int nq = buffer_.nq;
  buffer_.stamp.erase(buffer_.stamp.begin(), buffer_.stamp.begin() + drop);
  for (auto* v : {&buffer_.position, &buffer_.velocity, &buffer_.acceleration})
    v->erase(v->begin(), v->begin() + static_cast<size_t>(drop) * nq);
  buffer_.given.erase(buffer_.given.begin(),
                      buffer_.given.begin() + static_cast<size_t>(drop) * nq);
  next_ -= drop;
}

void OfflineStream::finish() {
  if (next_ < buffer_.rows()) compute(buffer_.rows());
}

}  // namespace mbk
