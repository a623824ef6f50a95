#include "mb_kinematics/offline/recording.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/estimation/outliers.h"

namespace mbk {
namespace {

std::string join(const std::vector<std::string>& names, size_t max = 8) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < max; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > max) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

}  // namespace

void Recording::snap_to_grid() {
  grid = find_stamp_grid(stamp, stamp_rounding);
  if (!grid.moves) return;
  recorded_stamp = stamp;
  for (double& t : stamp) t = grid.snap(t);
}

void DropLog::drop(const std::string& reason, const std::string& detail) {
  if (drops[reason]++ == 0) example[reason] = printable(detail);
}

void DropLog::note(const std::string& reason, const std::string& detail) {
  if (notes[reason]++ == 0) example[reason] = printable(detail);
}

long DropLog::dropped() const {
  long n = 0;
  for (const auto& d : drops) n += d.second;
  return n;
}

RecordingBuilder::RecordingBuilder(const Model& model)
    : model_(model), intake_(model), acceleration_names_(model), mimic_(model.nq, 0) {
  rec_.nq = model.nq;
  for (const Mimic& m : model.mimics) mimic_[m.coordinate] = 1;
}

void RecordingBuilder::add(double t, const std::vector<std::string>& names,
                           const std::vector<double>& position, const std::vector<double>& velocity,
                           const std::string& where) {
  ++read_;
  t += time_offset_;
  if (!std::isfinite(t)) return log_.drop("stamp not finite", where);
  const std::string error = intake_.check(names, position, velocity);
  if (!error.empty())
    return log_.drop("bad sample (lengths, duplicates, NaN/Inf)", where + ": " + error);
  if (has_last_stamp_ && t <= last_stamp_)
    return log_.drop(t == last_stamp_ ? "repeated stamp" : "stamp goes backwards",
                     where + ": stamp " + std::to_string(origin_ + t) + " after " +
                         std::to_string(origin_ + last_stamp_));
  if (!intake_.unknown().empty())
    log_.note("names not in the model ignored", where + ": " + join(intake_.unknown()));
  intake_.take(position);  // the named coordinates' positions, Euler parameters' signs aligned
  has_last_stamp_ = true, last_stamp_ = t;
  if (sink_) {  // as finish() drops the rows before every coordinate was named
    const std::vector<std::string> missing = not_named_yet();
    if (!missing.empty())
      return log_.drop("missing joints (not named yet)",
                       "sample at t = " + std::to_string(origin_ + t) + ": " + join(missing));
  }
  const int nq = model_.nq;
  PendingRow next = spare_row();
  next.t = t;
  next.row = intake_.last();  // the coordinates not named keep their last
  next.vrow.assign(nq, 0.0);
  next.given.assign(nq, 0);
  next.where = where;
  for (size_t m = 0; m < names.size(); ++m) {  // a mimic's published value wins (as the node)
    const int i = intake_.coordinates()[m];
    if (i < 0) continue;
    next.given[i] = Recording::kPosition;
    if (!velocity.empty())
      next.vrow[i] = intake_.sign(i) * velocity[m], next.given[i] |= Recording::kVelocity;
  }
  hold(std::move(next));
}

RecordingBuilder::PendingRow RecordingBuilder::spare_row() {
  if (spare_.empty()) return PendingRow();
  PendingRow r = std::move(spare_.back());
  spare_.pop_back();
  return r;
}

// The coordinates (mimics aside) no sample has named so far.
std::vector<std::string> RecordingBuilder::not_named_yet() const {
  std::vector<std::string> names;
  for (int i = 0; i < model_.nq; ++i)
    if (!mimic_[i] && !intake_.taken(i)) names.push_back(model_.coordinate_names[i]);
  return names;
}

void RecordingBuilder::hold(PendingRow pending) {
  constexpr int h = kOutlierHalfWindow, window = 2 * h + 1;
  pending_.push_back(std::move(pending));
  if (static_cast<int>(pending_.size()) < window) return;
  if (!tested_head_)
    for (int p = 0; p < h; ++p) test_outliers(p);
  tested_head_ = true;
  test_outliers(h);
  emit(pending_.front());
  spare_.push_back(std::move(pending_.front()));
  pending_.pop_front();
}

void RecordingBuilder::release_pending() {
  const int held = static_cast<int>(pending_.size());
  for (int p = tested_head_ ? kOutlierHalfWindow : 0; p < held; ++p) test_outliers(p);
  for (const PendingRow& r : pending_) emit(r);
  pending_.clear();
  tested_head_ = false;
}

void RecordingBuilder::test_outliers(int p) {
  constexpr int h = kOutlierHalfWindow, window = 2 * h + 1;
  const int held = static_cast<int>(pending_.size());
  const int lo = std::clamp(p - h, 0, std::max(0, held - window)), hi = std::min(held, lo + window);
  // The window's rows, looked up in the deque once for every coordinate (exclude_outlier changes
  // their values, never the rows themselves).
  const double* rows[window];
  const std::uint8_t* given[window];
  for (int q = lo; q < hi; ++q)
    rows[q - lo] = pending_[q].row.data(), given[q - lo] = pending_[q].given.data();
  const std::uint8_t* given_p = pending_[p].given.data();
  double values[window];
  for (int c = 0; c < model_.nq; ++c) {
    if (!(given_p[c] & Recording::kPosition)) continue;
    int count = 0;
    for (int q = 0; q < hi - lo; ++q)
      if (given[q][c] & Recording::kPosition) values[count++] = rows[q][c];
    if (count < kOutlierMinimumWindow) continue;
    const OutlierTest test = hampel_test(values, count, pending_[p].row[c]);
    if (test.outlier) exclude_outlier(p, c, test.median, test.scale);
  }
}

// Coordinate c of pending row p is not given there; its value (and the later rows' that kept
// it) becomes its window's median.
void RecordingBuilder::exclude_outlier(int p, int c, double median, double scale) {
  PendingRow& r = pending_[p];
  const double outlier = r.row[c];
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "%.6g, %.3g robust scales from its window's median %.6g",
                outlier, std::abs(outlier - median) / scale, median);
  log_.note("outliers excluded (Hampel's test, doc/recorded_data.md)",
            r.where + " (t = " + std::to_string(origin_ + r.t) + "): coordinate '" +
                model_.coordinate_names[c] + "' is " + numbers);
  r.row[c] = median, r.vrow[c] = 0, r.given[c] = 0;
  for (size_t q = p + 1; q < pending_.size(); ++q) {
    if (pending_[q].given[c] & Recording::kPosition) return;
    pending_[q].row[c] = median;
  }
  intake_.replace_last(c, median);
}

void RecordingBuilder::emit(const PendingRow& r) {
  if (sink_) return sink_(r.t, r.row.data(), r.vrow.data(), r.given.data());
  rec_.stamp.push_back(r.t);
  rec_.position.insert(rec_.position.end(), r.row.begin(), r.row.end());
  rec_.velocity.insert(rec_.velocity.end(), r.vrow.begin(), r.vrow.end());
  rec_.given.insert(rec_.given.end(), r.given.begin(), r.given.end());
}

void RecordingBuilder::add_accelerations(double t, const std::vector<std::string>& names,
                                         const std::vector<double>& acceleration,
                                         const std::string& where) {
  if (sink_) throw std::logic_error("RecordingBuilder: joint_accelerations while streaming");
  if (acceleration.size() != names.size())
    return log_.note("joint_accelerations ignored",
                     where + ": " + std::to_string(names.size()) + " names but " +
                         std::to_string(acceleration.size()) + " accelerations");
  std::vector<double> value(model_.nq, 0.0);
  std::vector<char> given(model_.nq, 0);
  const std::vector<int>& coordinate = acceleration_names_.look_up(names);
  for (size_t i = 0; i < names.size(); ++i) {
    const int c = coordinate[i];
    if (c < 0)
      return log_.note("joint_accelerations ignored",
                       where + ": joint '" + names[i] + "' is not in the model");
    if (given[c] || !std::isfinite(acceleration[i]))
      return log_.note("joint_accelerations ignored",
                       where + ": joint '" + names[i] + "' named twice or not finite");
    value[c] = acceleration[i];
    given[c] = 1;
  }
  accelerations_[t] = {std::move(value), std::move(given)};
}

Recording RecordingBuilder::finish() {
  release_pending();
  const int nq = model_.nq, rows = rec_.rows();
  const std::vector<std::string> never = not_named_yet();
  if (!never.empty() && read_ > 0) {
    std::string why = "no sample names the joints " + join(never);
    auto most = log_.drops.begin();  // why the samples that might have named them were dropped
    for (auto it = log_.drops.begin(); it != log_.drops.end(); ++it)
      if (it->second > most->second) most = it;
    if (most != log_.drops.end())
      why += " (" + std::to_string(log_.dropped()) + " of " + std::to_string(read_) +
             " samples dropped, " + std::to_string(most->second) + " as " + most->first +
             "; first: " + log_.example.at(most->first) + ")";
    throw std::invalid_argument(printable(why));
  }
  if (sink_) {
    Recording empty;
    empty.nq = nq;
    empty.origin = origin_;
    return empty;
  }
  // The first row from which every coordinate has a value; earlier rows are dropped.
  std::vector<char> named(nq, 0);
  int missing = 0, first = 0;
  for (int i = 0; i < nq; ++i) missing += !mimic_[i];
  for (; first < rows && missing > 0; ++first) {
    for (int i = 0; i < nq; ++i)
      if (!mimic_[i] && !named[i] && rec_.given[first * nq + i]) named[i] = 1, --missing;
    if (missing == 0) break;
    std::vector<std::string> names;
    for (int i = 0; i < nq; ++i)
      if (!mimic_[i] && !named[i]) names.push_back(model_.coordinate_names[i]);
    log_.drop("missing joints (not named yet)",
              "sample at t = " + std::to_string(origin_ + rec_.stamp[first]) + ": " + join(names));
  }
  // The builder's arrays move into the table (no copy beside them); the dropped rows go.
  Recording out = std::move(rec_);
  rec_ = Recording();
  rec_.nq = nq;
  out.stamp.erase(out.stamp.begin(), out.stamp.begin() + first);
  out.position.erase(out.position.begin(), out.position.begin() + first * nq);
  out.velocity.erase(out.velocity.begin(), out.velocity.begin() + first * nq);
  out.given.erase(out.given.begin(), out.given.begin() + first * nq);
  out.acceleration.assign(out.position.size(), 0.0);
  for (int r = 0; r < out.rows(); ++r) {
    auto it = accelerations_.find(out.stamp[r]);
    if (it == accelerations_.end()) continue;
    for (int i = 0; i < nq; ++i)
      if (it->second.second[i]) {
        out.acceleration[r * nq + i] = it->second.first[i];
        out.given[r * nq + i] |= Recording::kAcceleration;
      }
  }
  out.stamp_rounding = stamp_rounding_;
  out.origin = origin_;
  out.snap_to_grid();
  return out;
}

}  // namespace mbk
