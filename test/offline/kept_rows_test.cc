// KeptRows (offline/kept_rows.h): mbk bag's rows kept between its passes, in blocks.
#include "mb_kinematics/offline/kept_rows.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace {

constexpr int kNq = 3;

// Row r's values: every one distinct.
struct TestRow {
  explicit TestRow(long r) : t(0.001 * r) {
    for (int c = 0; c < kNq; ++c) {
      position[c] = r + 0.25 * c;
      velocity[c] = -r - 0.5 * c;
      given[c] = static_cast<std::uint8_t>((r + c) % 4);
    }
  }
  double t;
  double position[kNq], velocity[kNq];
  std::uint8_t given[kNq];
};

void keep_rows(mbk::KeptRows& kept, long rows) {
  for (long r = 0; r < rows; ++r) {
    const TestRow row(r);
    kept.keep(row.t, row.position, row.velocity, row.given);
  }
}

// Bytes per row: the stamp, the positions and velocities, the flags.
constexpr std::size_t kRowBytes = sizeof(double) * (1 + 2 * kNq) + kNq;

// Past the first blocks (a block holds 1 MiB of rows: 17,772 of 3 coordinates), every row reads
// back as it was kept, in order.
TEST(KeptRows, EveryRowBackInOrderAcrossBlocks) {
  const long rows = 50000;
  mbk::KeptRows kept(kNq, rows * kRowBytes);
  keep_rows(kept, rows);
  ASSERT_TRUE(kept.complete());
  ASSERT_EQ(kept.rows(), static_cast<std::size_t>(rows));
  for (long r = 0; r < rows; ++r) {
    const TestRow want(r);
    const mbk::KeptRows::Row got = kept.row(static_cast<std::size_t>(r));
    ASSERT_EQ(got.t, want.t) << r;
    for (int c = 0; c < kNq; ++c) {
      ASSERT_EQ(got.position[c], want.position[c]) << r;
      ASSERT_EQ(got.velocity[c], want.velocity[c]) << r;
      ASSERT_EQ(got.given[c], want.given[c]) << r;
    }
  }
}

// The bound holds exactly its rows; one more row forgets them all, and nothing is kept after.
TEST(KeptRows, OneRowPastTheBoundKeepsNone) {
  const long most = 20000;
  mbk::KeptRows exact(kNq, most * kRowBytes + kRowBytes - 1);
  keep_rows(exact, most);
  EXPECT_TRUE(exact.complete());
  EXPECT_EQ(exact.rows(), static_cast<std::size_t>(most));

  mbk::KeptRows over(kNq, most * kRowBytes);
  keep_rows(over, most + 1);
  EXPECT_FALSE(over.complete());
  EXPECT_EQ(over.rows(), 0u);  // none kept: no row() to read
  keep_rows(over, 10);
  EXPECT_FALSE(over.complete());
  EXPECT_EQ(over.rows(), 0u);
}

}  // namespace
