#include "mb_kinematics/io/number_format.h"

#include <charconv>
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

char* write_shortest(char* out, double x) {
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  return std::to_chars(out, out + kMaxDoubleChars, x + 0.0).ptr;
#else  // e.g. GCC 9 (ROS Noetic): no std::to_chars for double; always 17 digits
  return out + std::snprintf(out, kMaxDoubleChars, "%.17g", x + 0.0);
#endif
}

}  // namespace mbk
