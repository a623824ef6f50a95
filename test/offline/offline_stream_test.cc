// OfflineStream (offline/offline_stream.h): rows computed a chunk at a time as they arrive give
// the same results, bit for bit, as the whole recording at once (irregular stamps, gaps, a lone
// sample between gaps, the ends, velocities given in some rows), and it keeps a number of rows
// that does not grow with the recording's length.
#include "mb_kinematics/offline/offline_stream.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mb_kinematics/analysis/model_generators.h"
#include "test/support/test_models.h"

namespace {

// Sample i of a 1 kHz recording with jittered stamps, two gaps (at rows 700 and 1900), a lone
// sample between the second gap and a third (row 1900 alone); coordinate 6's velocity given in
// every row, coordinate 11's in rows 300..1500 only.
struct Sample {
  double t;
  std::vector<double> position, velocity;
  std::vector<std::uint8_t> given;
};

Sample sample(const mbk::Model& model, const mbk_test::Trajectory& trajectory, long i) {
  Sample s;
  s.t = 1e-3 * i + 3e-4 * std::sin(0.7 * i) + (i >= 700) * 0.5 + (i >= 1900) * 0.5 +
        (i >= 1901) * 0.5;
  const mbk::JointState<double> state = trajectory.at<double>(s.t);
  s.position.assign(state.position.data(), state.position.data() + model.nq);
  s.velocity.assign(model.nq, 0.0);
  s.given.assign(model.nq, mbk::Recording::kPosition);
  for (int c : {6, 11})  // of make_random_tree(6, 3): j3, j5 (one coordinate each)
    if (c == 6 || (i >= 300 && i < 1500))
      s.velocity[c] = state.velocity[c], s.given[c] |= mbk::Recording::kVelocity;
  return s;
}

struct Result {
  double stamp;
  std::string drop;
  mbk::Data<double> data;
  std::vector<mbk::Vec3<double>> alpha_se, acceleration_se;  // "auto"
};

void keep(std::vector<Result>& out, const mbk::OfflineRow& row) {
  out.push_back(
      {row.stamp, row.drop_reason + row.drop_detail, row.data, row.alpha_se, row.acceleration_se});
}

// "auto": every row's coordinate error bars (velocity, acceleration per coordinate) and the
// medians over the recording.
struct Errors {
  std::vector<std::vector<double>> rows;
  std::vector<mbk::CoordinateError> summary;
};

void keep_errors(const mbk::OfflineStates& states, int begin, int end, int nq, Errors& out) {
  std::vector<double> v(nq), a(nq);
  for (int r = begin; r < end; ++r) {
    ASSERT_TRUE(states.coordinate_errors(r, v.data(), a.data()));
    out.rows.push_back(v);
    out.rows.back().insert(out.rows.back().end(), a.begin(), a.end());
  }
}

void expect_same(const std::vector<Result>& a, const std::vector<Result>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t r = 0; r < a.size(); ++r) {
    ASSERT_EQ(a[r].stamp, b[r].stamp) << r;
    ASSERT_EQ(a[r].drop, b[r].drop) << r;
    if (!a[r].drop.empty()) continue;
    ASSERT_EQ(a[r].alpha_se, b[r].alpha_se) << r;
    ASSERT_EQ(a[r].acceleration_se, b[r].acceleration_se) << r;
    for (size_t k = 1; k < a[r].data.rotation.size(); ++k) {
      ASSERT_EQ(a[r].data.rotation[k], b[r].data.rotation[k]) << r << " body " << k;
      ASSERT_EQ(a[r].data.omega[k], b[r].data.omega[k]) << r << " body " << k;
      ASSERT_EQ(a[r].data.alpha[k], b[r].data.alpha[k]) << r << " body " << k;
      ASSERT_EQ(a[r].data.mass_center_acceleration[k], b[r].data.mass_center_acceleration[k])
          << r << " body " << k;
    }
  }
}

std::vector<Result> whole(const mbk::Model& model, const mbk::OfflineEstimator& e, long rows,
                          Errors* errors = nullptr) {
  const mbk_test::Trajectory trajectory(model, 2);
  mbk::Recording rec;
  rec.nq = model.nq;
  for (long i = 0; i < rows; ++i) {
    const Sample s = sample(model, trajectory, i);
    rec.stamp.push_back(s.t);
    rec.position.insert(rec.position.end(), s.position.begin(), s.position.end());
    rec.velocity.insert(rec.velocity.end(), s.velocity.begin(), s.velocity.end());
    rec.acceleration.insert(rec.acceleration.end(), model.nq, 0.0);
    rec.given.insert(rec.given.end(), s.given.begin(), s.given.end());
  }
  mbk::OfflineBatch batch(model, rec, e, 0, nullptr, 2);
  batch.set_body_errors(e.automatic);
  std::vector<Result> out;
  mbk::compute_rows(
      batch, model, 0, rec.rows(), [&](const mbk::OfflineRow& row) { keep(out, row); }, [](int) {});
  if (errors) {
    keep_errors(batch.states(), 0, rec.rows(), model.nq, *errors);
    errors->summary = batch.error_summary();
  }
  return out;
}

// "auto" chooses in a pass of its own first (AutoChoosePass); peak: the most rows either pass kept.
// error_bytes: what "auto" kept for the medians of its error bars.
std::vector<Result> streamed(const mbk::Model& model, const mbk::OfflineEstimator& e, long rows,
                             int chunk, int* peak = nullptr, Errors* errors = nullptr,
                             std::size_t* error_bytes = nullptr) {
  const mbk_test::Trajectory trajectory(model, 2);
  mbk::RecordingSurvey survey(model.nq, true, 64);  // few bins: the stamps surveyed again
  for (long i = 0; i < rows; ++i) {
    const Sample s = sample(model, trajectory, i);
    survey.add(s.t, s.given.data());
  }
  while (!survey.finish_pass())
    for (long i = 0; i < rows; ++i) survey.add_stamp(sample(model, trajectory, i).t);
  EXPECT_GT(survey.intervals.passes(), 1);
  EXPECT_TRUE(survey.streamable());
  mbk::OfflineReach reach;
  mbk::WholeRecording whole;
  whole.velocity_everywhere = survey.velocity_everywhere;
  int peak_choosing = 0;
  if (e.automatic) {
    mbk::AutoChoosePass pass(model, survey, survey.default_max_gap(), chunk);
    for (long i = 0; i < rows; ++i) {
      const Sample s = sample(model, trajectory, i);
      pass.add(s.t, s.position.data(), s.velocity.data());
    }
    whole = pass.finish(reach);
    peak_choosing = pass.peak_buffered_rows();
  } else {
    EXPECT_TRUE(mbk::offline_reach(e, reach));
  }
  std::vector<Result> out;
  mbk::OfflineStream stream(model, e, reach, survey.default_max_gap(), whole, 2, chunk,
                            [&](const mbk::OfflineRow& row) { keep(out, row); });
  stream.set_body_errors(e.automatic);
  if (errors)
    stream.set_chunk_hook([&](const mbk::OfflineStates& states, const mbk::Recording&, int begin,
                              int end) { keep_errors(states, begin, end, model.nq, *errors); });
  for (long i = 0; i < rows; ++i) {
    const Sample s = sample(model, trajectory, i);
    stream.add(s.t, s.position.data(), s.velocity.data(), s.given.data());
  }
  stream.finish();
  if (peak) *peak = std::max(peak_choosing, stream.peak_buffered_rows());
  if (errors) errors->summary = stream.error_summary();
  if (error_bytes) *error_bytes = stream.error_bytes();
  return out;
}

TEST(OfflineStreamTest, ChunkByChunkEqualsTheWholeRecordingBitForBit) {
  const mbk::Model model = mbk::make_random_tree(6, 3);  // joints of every type
  for (const char* name : {"centered_0.4s_4", "centered_0.1s_3", "centered_9_4"}) {
    SCOPED_TRACE(name);
    const mbk::OfflineEstimator e = mbk::make_offline_estimator(name);
    const std::vector<Result> all = whole(model, e, 2600);
    int drops = 0;
    for (const Result& r : all) drops += !r.drop.empty();
    EXPECT_EQ(drops, 1);  // the lone sample
    for (int chunk : {7, 300, 5000}) expect_same(all, streamed(model, e, 2600, chunk));
  }
}

// "auto", the default: a choice pass over the pieces (AutoChoosePass), then the chosen windows a
// chunk at a time give the whole recording's estimates, body and coordinate error bars and their
// medians, bit for bit.
TEST(OfflineStreamTest, AutoChunkByChunkEqualsTheWholeRecordingBitForBit) {
  const mbk::Model model = mbk::make_random_tree(6, 3);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("auto");
  Errors all_errors;
  const std::vector<Result> all = whole(model, e, 2600, &all_errors);
  ASSERT_FALSE(all_errors.summary.empty());
  for (int chunk : {50, 700, 5000}) {
    SCOPED_TRACE(chunk);
    Errors errors;
    expect_same(all, streamed(model, e, 2600, chunk, nullptr, &errors));
    EXPECT_EQ(errors.rows, all_errors.rows);
    ASSERT_EQ(errors.summary.size(), all_errors.summary.size());
    for (size_t c = 0; c < errors.summary.size(); ++c) {
      const mbk::CoordinateError &a = errors.summary[c], &b = all_errors.summary[c];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.noise, b.noise) << a.name;
      EXPECT_EQ(a.velocity_se, b.velocity_se) << a.name;
      EXPECT_EQ(a.acceleration_se, b.acceleration_se) << a.name;
    }
  }
}

TEST(OfflineStreamTest, SurveyFindsTheWholeRecordingsMaxGap) {
  const mbk::Model model = mbk::make_random_tree(6, 3);
  const mbk_test::Trajectory trajectory(model, 2);
  mbk::RecordingSurvey survey(model.nq);
  std::vector<double> t;
  for (long i = 0; i < 999; ++i) {
    const Sample s = sample(model, trajectory, i);
    survey.add(s.t, s.given.data());
    t.push_back(s.t);
  }
  EXPECT_TRUE(survey.finish_pass());
  EXPECT_EQ(survey.default_max_gap(), mbk::default_max_gap(t));
  EXPECT_EQ(survey.rows, 999);
}

// Stamps with every interval distinct (jitter): the survey's memory stays within its bins' bound
// for 10^5 rows as for 10^6, at the cost of a second pass over the stamps, and the median is the
// whole recording's, bit for bit.
TEST(OfflineStreamTest, SurveyOfJitteredStampsTakesBoundedMemory) {
  const std::vector<std::uint8_t> given(1, mbk::Recording::kPosition);
  for (long rows : {100000L, 1000000L}) {
    std::vector<double> t;
    for (long i = 0; i < rows; ++i) t.push_back(1 + 1e-3 * i + 3e-4 * std::sin(0.7 * i));
    mbk::RecordingSurvey survey(1);
    for (double x : t) survey.add(x, given.data());
    int passes = 1;
    for (; !survey.finish_pass(); ++passes)
      for (double x : t) survey.add_stamp(x);
    EXPECT_EQ(passes, 2) << rows;
    EXPECT_EQ(survey.default_max_gap(), mbk::default_max_gap(t)) << rows;
    EXPECT_LE(survey.intervals.peak_bytes(), ((1u << 14) + 1) * 48) << rows;
    EXPECT_EQ(survey.rows, rows);
  }
}

// The rows `e` keeps on a recording generated on the fly, never held: below a bound set by the
// chunk and `reach` at 1 kHz, the same for 10 s as for 50 s.
void expect_rows_kept_bounded(const char* name, const mbk::OfflineReach& reach) {
  const mbk::Model model = mbk::make_random_tree(6, 3);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator(name);
  const int chunk = 1000;
  const int bound = chunk + 2 * static_cast<int>(1000 * reach.seconds * 1.01 + reach.samples + 3);
  int peak_short = 0, peak_long = 0;
  EXPECT_EQ(streamed(model, e, 10000, chunk, &peak_short).size(), 10000u);
  EXPECT_EQ(streamed(model, e, 50000, chunk, &peak_long).size(), 50000u);
  EXPECT_LE(peak_long, bound);
  EXPECT_EQ(peak_long, peak_short);
}

// The estimator's reach: 0.4 s.
TEST(OfflineStreamTest, RowsKeptDoNotGrowWithTheRecording) {
  mbk::OfflineReach reach;
  ASSERT_TRUE(mbk::offline_reach(mbk::make_offline_estimator("centered_0.4s_4"), reach));
  expect_rows_kept_bounded("centered_0.4s_4", reach);
}

// "auto": its longest candidate's reach (641 intervals of 1 ms), in its choice pass as in its
// estimating one.
TEST(OfflineStreamTest, AutoRowsKeptDoNotGrowWithTheRecording) {
  mbk::OfflineReach reach;
  ASSERT_TRUE(mbk::offline_reach(mbk::auto_candidates(1e-3).back(), reach));
  expect_rows_kept_bounded("auto", reach);
}

// "auto": the error bars' medians (ErrorColumns) take memory by the octaves the standard errors
// span, not by the samples: 50 s take at most a few octaves more than 10 s (a rarer tail value),
// far from the 5x of every value kept, and at most 12 octaves of bins per column.
TEST(OfflineStreamTest, AutoErrorMediansDoNotGrowWithTheRecording) {
  const mbk::Model model = mbk::make_random_tree(6, 3);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("auto");
  std::size_t short_bytes = 0, long_bytes = 0;
  streamed(model, e, 10000, 1000, nullptr, nullptr, &short_bytes);
  streamed(model, e, 50000, 1000, nullptr, nullptr, &long_bytes);
  EXPECT_GT(short_bytes, 0u);
  EXPECT_LE(long_bytes, short_bytes * 5 / 4);
  EXPECT_LE(long_bytes, static_cast<std::size_t>(2 * model.nq * 12 * 32768));
}

// ... and a short recording of a large model takes what its values take (8 bytes each, the
// vector's growth aside), not 32 KiB per column: 200 samples of 400 bodies.
TEST(OfflineStreamTest, AutoErrorMediansOfAShortRecordingTakeItsValues) {
  const mbk::Model model = mbk::make_random_tree(400, 5);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("auto");
  std::size_t bytes = 0;
  EXPECT_EQ(streamed(model, e, 200, 1000, nullptr, nullptr, &bytes).size(), 200u);
  EXPECT_GT(bytes, 0u);
  EXPECT_LE(bytes, static_cast<std::size_t>(2 * model.nq * 256 * 8));
}

// RecordingBuilder::stream_to hands out the rows finish() keeps and drops the same ones, counted
// the same way.
TEST(OfflineStreamTest, StreamingBuilderKeepsAndDropsTheRowsOfTheTable) {
  const mbk::Model model = mbk::make_random_revolute_tree(2, 1);  // coordinates of two joints
  const std::string j1 = model.coordinate_names[0], j2 = model.coordinate_names[1];
  mbk::RecordingBuilder table(model), stream(model);
  std::vector<double> stamps;
  stream.stream_to(
      [&](double t, const double*, const double*, const std::uint8_t*) { stamps.push_back(t); });
  for (mbk::RecordingBuilder* b : {&table, &stream}) {
    b->add(0.0, {j1}, {0.1}, {}, "s0");  // j2 not named yet: dropped
    b->add(0.1, {j1, j2}, {0.1, 0.2}, {}, "s1");
    b->add(0.1, {j1, j2}, {0.1, 0.2}, {}, "s2");  // repeated stamp
    b->add(0.2, {j2}, {0.3}, {}, "s3");
  }
  const mbk::Recording r = table.finish();
  stream.finish();
  EXPECT_EQ(stamps, r.stamp);
  EXPECT_EQ(stream.log().drops, table.log().drops);
  EXPECT_EQ(stream.log().example, table.log().example);
}

}  // namespace
