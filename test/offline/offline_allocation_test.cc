// mbk bag's computation allocates nothing per row (doc/recorded_data.md): once OfflineBatch has
// done its first block, estimates (of coordinates given in every row and of those with their
// own samples), state checks and kinematics of further rows reuse what exists, and so does the
// pool of workers (started once, not per block). With one worker: several take chunks as they
// come, so a worker may do its first row (and size its scratch) in a later block. Counted with
// the replaced operator new and malloc of test/support/allocation_counter.h.
#include <gtest/gtest.h>

#include <cmath>

#include "mb_kinematics/offline/offline_batch.h"
#include "test/support/allocation_counter.h"
#include "test/support/test_models.h"

namespace {

// 1 kHz positions of a random tree; coordinate 0 only in every other row (a series of its own).
mbk::Recording recording(const mbk::Model& model, int rows) {
  const mbk_test::Trajectory trajectory(model, 1);
  mbk::Recording r;
  r.nq = model.nq;
  for (int i = 0; i < rows; ++i) {
    const double t = 1e-3 * i;
    const mbk::JointState<double> s = trajectory.at<double>(t);
    r.stamp.push_back(t);
    for (int c = 0; c < model.nq; ++c) {
      r.position.push_back(s.position[c]);
      r.velocity.push_back(0), r.acceleration.push_back(0);
      r.given.push_back(c == 0 && i % 2 ? 0 : mbk::Recording::kPosition);
    }
  }
  return r;
}

class OfflineAllocation : public ::testing::TestWithParam<int> {};

TEST_P(OfflineAllocation, NoneWhileComputingRowsAfterTheFirstBlock) {
  const mbk::Model model = mbk_test::random_tree(30, 1);
  const mbk::Recording rec = recording(model, 600);
  mbk::OfflineBatch batch(model, rec, mbk::make_offline_estimator("centered_0.1s_4"), 0, nullptr,
                          GetParam());
  std::vector<mbk::OfflineRow> rows(200, mbk::OfflineRow(model));
  batch.compute(0, 200, rows);
  const mbk_test::AllocationCounts before = mbk_test::allocation_counts();
  batch.compute(200, 400, rows);
  const mbk_test::AllocationCounts after = mbk_test::allocation_counts();
  EXPECT_EQ(after.news, before.news) << "operator new while computing rows";
  EXPECT_EQ(after.mallocs, before.mallocs) << "malloc while computing rows";
  for (const mbk::OfflineRow& row : rows) {
    ASSERT_EQ(row.drop_reason, "") << row.drop_detail;
    ASSERT_TRUE(std::isfinite(row.data.mass_center_acceleration.back().x()));
  }
  EXPECT_EQ(rows.front().stamp, rec.stamp[200]);
  EXPECT_EQ(rows.back().stamp, rec.stamp[399]);
}

// compute_rows makes the rows it computes, not a whole block's: 8 rows of a recording make about
// 8 rows (a run of whole blocks made and never touched was most of a short recording's page
// faults in mbk bag).
TEST(OfflineAllocation, ComputeRowsMakesTheRowsItComputes) {
  const mbk::Model model = mbk_test::random_tree(30, 1);
  const mbk::Recording rec = recording(model, 600);
  mbk::OfflineBatch batch(model, rec, mbk::make_offline_estimator("centered_0.1s_4"), 0, nullptr,
                          1);
  const auto rows = [&](int begin, int end) {
    mbk::compute_rows(
        batch, model, begin, end, [](const mbk::OfflineRow&) {}, [](int) {});
  };
  rows(0, 8);  // the worker's first rows size its scratch
  const mbk::OfflineRow blank(model);
  long before = mbk_test::allocation_counts().news;
  { const mbk::OfflineRow copy = blank; }
  const long per_row = mbk_test::allocation_counts().news - before;
  before = mbk_test::allocation_counts().news;
  rows(8, 16);
  const long made = mbk_test::allocation_counts().news - before;
  ASSERT_GT(per_row, 0);
  EXPECT_LE(made, 2 * 8 * per_row) << "about " << made / per_row << " rows made for 8";
  EXPECT_GT(batch.rows_per_block(4 << 20), 2 * 8) << "a block holds more rows than this test's";
}

INSTANTIATE_TEST_SUITE_P(Threads, OfflineAllocation, ::testing::Values(1));

}  // namespace
