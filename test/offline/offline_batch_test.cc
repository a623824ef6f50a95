// OfflineBatch (offline/offline_batch.h): its pool of workers gives every row the same result, bit
// for bit, whatever the number of threads, the blocks' sizes and which worker takes which
// chunk; dropped rows keep their reason; start() returns while the block is computed.
#include "mb_kinematics/offline/offline_batch.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <new>
#include <set>
#include <stdexcept>
#include <thread>

#include "test/support/test_models.h"

namespace {

// 1 kHz positions of a random tree; coordinate 0 only in every third row (a series of its
// own), and a NaN at row 250 (a row check_state drops).
mbk::Recording recording(const mbk::Model& model, int rows) {
  const mbk_test::Trajectory trajectory(model, 2);
  mbk::Recording r;
  r.nq = model.nq;
  for (int i = 0; i < rows; ++i) {
    const double t = 1e-3 * i;
    const mbk::JointState<double> s = trajectory.at<double>(t);
    r.stamp.push_back(t);
    for (int c = 0; c < model.nq; ++c) {
      const bool nan = i == 250 && c == 1;
      r.position.push_back(nan ? std::numeric_limits<double>::quiet_NaN() : s.position[c]);
      r.velocity.push_back(0), r.acceleration.push_back(0);
      r.given.push_back(c == 0 && i % 3 ? 0 : mbk::Recording::kPosition);
    }
  }
  return r;
}

// Every row of the recording through `batch`, in blocks of the given sizes (cycled).
std::vector<mbk::OfflineRow> run(mbk::OfflineBatch& batch, const mbk::Model& model, int rows,
                                 const std::vector<int>& blocks) {
  std::vector<mbk::OfflineRow> all, block(64, mbk::OfflineRow(model));
  for (int begin = 0, b = 0; begin < rows; ++b) {
    const int end = std::min(rows, begin + blocks[b % blocks.size()]);
    batch.compute(begin, end, block);
    all.insert(all.end(), block.begin(), block.begin() + (end - begin));
    begin = end;
  }
  return all;
}

void expect_same(const mbk::OfflineRow& a, const mbk::OfflineRow& b, int r) {
  ASSERT_EQ(a.stamp, b.stamp) << r;
  ASSERT_EQ(a.drop_reason, b.drop_reason) << r;
  if (!a.drop_reason.empty()) return;
  EXPECT_EQ(a.state.velocity, b.state.velocity) << r;
  EXPECT_EQ(a.state.acceleration, b.state.acceleration) << r;
  for (size_t k = 1; k < a.data.rotation.size(); ++k) {
    ASSERT_EQ(a.data.rotation[k], b.data.rotation[k]) << r << " body " << k;
    ASSERT_EQ(a.data.alpha[k], b.data.alpha[k]) << r << " body " << k;
    ASSERT_EQ(a.data.mass_center_acceleration[k], b.data.mass_center_acceleration[k])
        << r << " body " << k;
  }
}

TEST(OfflineBatchTest, EveryThreadCountAndBlockSplitGivesTheSameRows) {
  const mbk::Model model = mbk_test::random_tree(12, 3);
  const int rows = 400;
  const mbk::Recording rec = recording(model, rows);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_0.05s_4");
  mbk::OfflineBatch one(model, rec, e, 0, nullptr, 1);
  const std::vector<mbk::OfflineRow> expected = run(one, model, rows, {64});
  ASSERT_EQ(static_cast<int>(expected.size()), rows);
  EXPECT_NE(expected[250].drop_reason, "");  // the NaN row
  EXPECT_EQ(expected[320].drop_reason, "");  // beyond the window of the NaN
  for (int threads : {2, 3, 7})
    for (const std::vector<int>& blocks : std::vector<std::vector<int>>{{64}, {1, 7, 13}, {5}}) {
      mbk::OfflineBatch batch(model, rec, e, 0, nullptr, threads);
      const std::vector<mbk::OfflineRow> got = run(batch, model, rows, blocks);
      ASSERT_EQ(got.size(), expected.size());
      for (int r = 0; r < rows; ++r) expect_same(got[r], expected[r], r);
    }
}

// The caller works (writes the block before) between start() and finish(); finish() returns
// the workers' seconds, and a batch ends cleanly whether or not it ever ran a block.
TEST(OfflineBatchTest, StartReturnsAndFinishWaits) {
  const mbk::Model model = mbk_test::random_tree(12, 3);
  const mbk::Recording rec = recording(model, 200);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_0.05s_4");
  { mbk::OfflineBatch idle(model, rec, e, 0, nullptr, 4); }
  mbk::OfflineBatch batch(model, rec, e, 0, nullptr, 2);
  std::vector<mbk::OfflineRow> rows(100, mbk::OfflineRow(model));
  batch.start(100, 200, rows);
  const double seconds = batch.finish();
  EXPECT_GT(seconds, 0);
  EXPECT_EQ(rows.front().stamp, rec.stamp[100]);
  EXPECT_EQ(rows.back().stamp, rec.stamp[199]);
  EXPECT_EQ(rows.back().drop_reason, "");
  EXPECT_EQ(batch.finish(), seconds) << "a second finish() waits for nothing";
}

// What a worker throws (std::bad_alloc when mbk bag's --max-memory refuses an allocation) comes
// out of compute() in the caller's thread, once, instead of ending the process; the pool then
// computes the next block as before.
TEST(OfflineBatchTest, AWorkersExceptionReachesTheCaller) {
  const mbk::Model model = mbk_test::random_tree(6, 3);
  const mbk::Recording rec = recording(model, 100);
  const mbk::OfflineEstimator e = mbk::make_offline_estimator("centered_0.05s_4");
  for (int threads : {1, 3}) {
    mbk::OfflineBatch batch(model, rec, e, 0, nullptr, threads);
    bool refuse = true;
    batch.set_formatter([&](mbk::OfflineRow&) {
      if (refuse) throw std::bad_alloc();
    });
    std::vector<mbk::OfflineRow> block(64, mbk::OfflineRow(model));
    EXPECT_THROW(batch.compute(0, 64, block), std::bad_alloc) << threads;
    refuse = false;
    EXPECT_NO_THROW(batch.compute(0, 64, block)) << threads;
    EXPECT_EQ(block[63].drop_reason, "");
  }
}

// compute_rows hands every row over once, in order, and keeps the formatted texts of the rows it
// holds at once (two blocks) within twice its 4 MB budget, counting the first block's texts: the
// texts of 600 rows of 64 KiB each (38 MiB) are not all alive at once.
TEST(OfflineBatchTest, ComputeRowsKeepsTheRowsTextsWithinItsBudget) {
  const mbk::Model model = mbk_test::random_tree(12, 3);
  const int rows = 600;
  const std::size_t text = std::size_t{64} << 10;
  const mbk::Recording rec = recording(model, rows);
  mbk::OfflineBatch batch(model, rec, mbk::make_offline_estimator("centered_0.05s_4"), 0, nullptr,
                          2);
  std::mutex mutex;
  std::set<const char*> texts;  // the distinct buffers the formatter filled
  batch.set_formatter([&](mbk::OfflineRow& row) {
    row.text.assign(text, 'x');
    std::lock_guard<std::mutex> lock(mutex);
    texts.insert(row.text.data());
  });
  std::vector<double> stamps;
  mbk::compute_rows(
      batch, model, 0, rows, [&](const mbk::OfflineRow& row) { stamps.push_back(row.stamp); },
      [](int) {});
  ASSERT_EQ(stamps, rec.stamp);
  const std::size_t first_block = batch.rows_per_block(0);
  EXPECT_LE(texts.size() * text, 2 * (std::size_t{4} << 20) + first_block * text)
      << texts.size() << " texts";
}

// What `use` throws (mbk bag refusing a row's stamp) leaves compute_rows only once the block in
// flight is done: its workers write into compute_rows' rows, which the exception frees.
TEST(OfflineBatchTest, ComputeRowsWaitsForTheBlockInFlightWhenUseThrows) {
  const mbk::Model model = mbk_test::random_tree(12, 3);
  const mbk::Recording rec = recording(model, 400);
  mbk::OfflineBatch batch(model, rec, mbk::make_offline_estimator("centered_0.05s_4"), 0, nullptr,
                          2);
  std::atomic<bool> left{false};
  std::atomic<int> after{0};  // rows formatted once compute_rows had thrown
  batch.set_formatter([&](mbk::OfflineRow&) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    if (left) ++after;
  });
  EXPECT_THROW(
      mbk::compute_rows(
          batch, model, 0, 400,
          [](const mbk::OfflineRow&) { throw std::invalid_argument("refused"); }, [](int) {}),
      std::invalid_argument);
  left = true;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(after, 0) << "rows computed into freed rows";
}

}  // namespace
