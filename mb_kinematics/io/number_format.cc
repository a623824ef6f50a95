#include "mb_kinematics/io/number_format.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>

namespace mbk {

char* write_shortest(char* out, double x) {
  x += 0.0;  // -0 as 0
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  return std::to_chars(out, out + kMaxDoubleChars, x).ptr;
#else
  int n = 0;
  for (int digits = 15; digits <= 17; ++digits) {
    n = std::snprintf(out, kMaxDoubleChars, "%.*g", digits, x);
    if (std::strtod(out, nullptr) == x) break;
  }
  return out + n;
#endif
}

char* write_general(char* out, double x, int precision) {
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  return std::to_chars(out, out + kMaxDoubleChars, x, std::chars_format::general, precision).ptr;
#else
  return out + std::snprintf(out, kMaxDoubleChars, "%.*g", precision, x);
#endif
}

std::string format_double(double x) {
  char text[kMaxDoubleChars];
  return std::string(text, write_shortest(text, x));
}

}  // namespace mbk
