// Numerical stability, group "size_shape": every case of mbk::stability_cases("size_shape") within
// the bound derived next to it in mb_kinematics/analysis/stability.cc.
#include <gtest/gtest.h>

#include "mb_kinematics/analysis/stability.h"

namespace {

TEST(SizeAndShape, EveryCaseWithinItsBound) {
  const std::vector<mbk::StabilityRow> rows = mbk::stability_cases("size_shape");
  ASSERT_FALSE(rows.empty());
  for (const mbk::StabilityRow& row : rows)
    EXPECT_LE(row.measured, row.bound) << row.name << " | " << row.quantity << " | " << row.note;
  std::printf("%s", mbk::format_stability_table(rows).c_str());
}

}  // namespace
