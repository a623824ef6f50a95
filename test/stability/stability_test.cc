// Numerical stability: every case of each group of mbk::stability_cases within the bound
// derived next to it in mb_kinematics/analysis/stability.cc (doc/stability.md).
// One test per group; a failure names the case, the quantity and the derivation's note.
#include "mb_kinematics/analysis/stability.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace {

class StabilityGroup : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilityGroup, EveryCaseWithinItsBound) {
  const std::vector<mbk::StabilityRow> rows = mbk::stability_cases(GetParam());
  ASSERT_FALSE(rows.empty());
  for (const mbk::StabilityRow& row : rows)
    EXPECT_LE(row.measured, row.bound) << row.name << " | " << row.quantity << " | " << row.note;
  std::printf("%s", mbk::format_stability_table(rows).c_str());
}

INSTANTIATE_TEST_SUITE_P(Groups, StabilityGroup, ::testing::ValuesIn(mbk::stability_groups()),
                         [](const auto& info) { return info.param; });

}  // namespace
