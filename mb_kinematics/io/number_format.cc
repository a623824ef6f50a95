#include "mb_kinematics/io/number_format.h"

#include <cstdio>
#include <cstdlib>

namespace mbk {

std::string format_double(double x) {
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x + 0.0);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

}  // namespace mbk
