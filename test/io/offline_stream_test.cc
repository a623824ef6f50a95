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
};

void keep(std::vector<Result>& out, const mbk::OfflineRow& row) {
  out.push_back({row.stamp, row.drop_reason + row.drop_detail, row.data});
}

void expect_same(const std::vector<Result>& a, const std::vector<Result>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t r = 0; r < a.size(); ++r) {
    ASSERT_EQ(a[r].stamp, b[r].stamp) << r;
    ASSERT_EQ(a[r].drop, b[r].drop) << r;
    if (!a[r].drop.empty()) continue;
    for (size_t k = 1; k < a[r].data.rotation.size(); ++k) {
      ASSERT_EQ(a[r].data.rotation[k], b[r].data.rotation[k]) << r << " body " << k;
      ASSERT_EQ(a[r].data.omega[k], b[r].data.omega[k]) << r << " body " << k;
      ASSERT_EQ(a[r].data.alpha[k], b[r].data.alpha[k]) << r << " body " << k;
      ASSERT_EQ(a[r].data.mass_center_acceleration[k], b[r].data.mass_center_acceleration[k])
          << r << " body " << k;
    }
  }
}

std::vector<Result> whole(const mbk::Model& model, const mbk::OfflineEstimator& e, long rows) {
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
  std::vector<Result> out;
  mbk::compute_rows(
      batch, model, 0, rec.rows(), [&](const mbk::OfflineRow& row) { keep(out, row); }, [](int) {});
  return out;
}

std::vector<Result> streamed(const mbk::Model& model, const mbk::OfflineEstimator& e, long rows,
                             int chunk, int* peak = nullptr) {
  const mbk_test::Trajectory trajectory(model, 2);
  mbk::RecordingSurvey survey(model.nq);
  for (long i = 0; i < rows; ++i) {
    const Sample s = sample(model, trajectory, i);
    survey.add(s.t, s.given.data());
  }
  EXPECT_TRUE(survey.streamable());
  mbk::OfflineReach reach;
  EXPECT_TRUE(mbk::offline_reach(e, reach));
  std::vector<Result> out;
  mbk::OfflineStream stream(model, e, reach, survey.default_max_gap(), survey.velocity_everywhere,
                            2, chunk, [&](const mbk::OfflineRow& row) { keep(out, row); });
  for (long i = 0; i < rows; ++i) {
    const Sample s = sample(model, trajectory, i);
    stream.add(s.t, s.position.data(), s.velocity.data(), s.given.data());
  }
  stream.finish();
  if (peak) *peak = stream.peak_buffered_rows();
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
  EXPECT_EQ(survey.default_max_gap(), mbk::default_max_gap(t));
  EXPECT_EQ(survey.rows, 999);
}

// A recording generated on the fly, never held: the rows kept stay below a bound set by the
// chunk and the estimator's reach (0.4 s at 1 kHz), the same for 10 s as for 50 s.
TEST(OfflineStreamTest, RowsKeptDoNotGrowWithTheRecording) {
  const mbk::Model model = mbk::make_random_tree(6, 3);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_0.4s_4");
  mbk::OfflineReach reach;
  ASSERT_TRUE(mbk::offline_reach(e, reach));
  const int chunk = 1000;
  const int bound = chunk + 2 * static_cast<int>(1000 * reach.seconds * 1.01 + reach.samples + 3);
  int peak_short = 0, peak_long = 0;
  EXPECT_EQ(streamed(model, e, 10000, chunk, &peak_short).size(), 10000u);
  EXPECT_EQ(streamed(model, e, 50000, chunk, &peak_long).size(), 50000u);
  EXPECT_LE(peak_long, bound);
  EXPECT_EQ(peak_long, peak_short);
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
