// mbk_stability_report: the table of the numerical stability suite
// (doc/stability.md; test/stability/ asserts the same rows). Prints markdown:
// case | quantity | measured | bound | note, one section per group.
//   mbk_stability_report [GROUP...]   (default: every group)
#include <cstdio>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/stability.h"

int main(int argc, char** argv) {
  std::vector<std::string> groups(argv + 1, argv + argc);
  if (groups.empty()) groups = mbk::stability_groups();
  int failed = 0;
  for (const std::string& group : groups) {
    const std::vector<mbk::StabilityRow> rows = mbk::stability_cases(group);
    if (rows.empty()) {
      std::fprintf(stderr, "mbk_stability_report: unknown group '%s'\n", group.c_str());
      return 2;
    }
    std::printf("\n### %s\n\n%s", group.c_str(), mbk::format_stability_table(rows).c_str());
    std::fflush(stdout);
    for (const auto& row : rows) failed += !row.ok();
  }
  std::printf("\n(eps = 2^-53; per-link bound = %g = %g x %g roundings x eps)\n", mbk::kLinkBound,
              mbk::kSafety, mbk::kRoundingsPerLink);
  return failed ? 1 : 0;
}
