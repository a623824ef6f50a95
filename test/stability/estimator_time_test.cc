// Numerical stability, group "estimator_time": every case of mbk::stability_cases("estimator_time")
// within the bound derived next to it in mb_kinematics/analysis/stability.cc.
#include <gtest/gtest.h>

#include "mb_kinematics/analysis/stability.h"

namespace {

TEST(EstimatorTime, EveryCaseWithinItsBound) {
  const std::vector<mbk::StabilityRow> rows = mbk::stability_cases("estimator_time");
  ASSERT_FALSE(rows.empty());
  for (const mbk::StabilityRow& row : rows)
    EXPECT_LE(row.measured, row.bound) << row.name << " | " << row.quantity << " | " << row.note;
  std::printf("%s", mbk::format_stability_table(rows).c_str());
}

}  // namespace
