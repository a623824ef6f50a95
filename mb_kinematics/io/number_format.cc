#include "mb_kinematics/io/number_format.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#if __has_include(<fmt/format.h>)
#include <fmt/format.h>
#endif
#if defined(FMT_VERSION) && FMT_VERSION >= 80000
#define MBK_HAVE_DRAGONBOX 1  // fmt's shortest decimal (Dragonbox): about 3x std::to_chars
#endif

namespace mbk {

std::string format_double(double x) {
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x + 0.0);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

namespace {

#ifdef MBK_HAVE_DRAGONBOX
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Decimal digits of m > 0.
int digit_count(uint64_t m) {
  static constexpr uint64_t kPow10[] = {1,
                                        10,
                                        100,
                                        1000,
                                        10000,
                                        100000,
                                        1000000,
                                        10000000,
                                        100000000,
                                        1000000000,
                                        10000000000,
                                        100000000000,
                                        1000000000000,
                                        10000000000000,
                                        100000000000000,
                                        1000000000000000,
                                        10000000000000000,
                                        100000000000000000,
                                        1000000000000000000,
                                        10000000000000000000u};
  const int t = ((64 - __builtin_clzll(m)) * 1233) >> 12;  // 1233/4096 ~ log10(2)
  return t + (m >= kPow10[t]);
}

// The n digits of m written at out[0, n), two at a time from the right.
void write_digits(char* out, uint64_t m, int n) {
  char* p = out + n;
  for (; m >= 100; m /= 100) std::memcpy(p -= 2, kPairs + 2 * (m % 100), 2);
  if (m >= 10)
    std::memcpy(p - 2, kPairs + 2 * m, 2);
  else
    p[-1] = static_cast<char>('0' + m);
}

// m * 10^e (m without trailing zeros, n digits) as std::to_chars(first, last, x) writes it:
// fixed when not longer than scientific (libstdc++'s bounds), scientific as "d.ddde+XX".
// nullptr for a whole number too large to be exact from m and e (std::to_chars prints those).
char* write_decimal(char* out, bool negative, uint64_t m, int e) {
  if (negative) *out++ = '-';
  const int n = digit_count(m);
  const int lower = n == 1 ? -3 : -(n + 3), upper = n == 1 ? 4 : 5;
  if (e >= lower && e <= upper) {
    if (e >= 0) {
      if ((63 - __builtin_clzll(m)) + (e * 10 + 2) / 3 >= 50) return nullptr;
      write_digits(out, m, n);
      std::memset(out + n, '0', e);
      return out + n + e;
    }
    if (n <= -e) {  // below 1: "0.00ddd"
      const int zeros = -e - n;
      std::memcpy(out, "0.", 2);
      std::memset(out + 2, '0', zeros);
      write_digits(out + 2 + zeros, m, n);
      return out + 2 + zeros + n;
    }
    write_digits(out, m, n);  // "ddd.ddd": the point moved in
    const int whole = n + e;
    std::memmove(out + whole + 1, out + whole, -e);
    out[whole] = '.';
    return out + n + 1;
  }
  write_digits(out + 1, m, n);  // "d.ddde+XX"
  out[0] = out[1];
  char* p = out + 1;
  if (n > 1) *p++ = '.', p += n - 1;
  int x = e + n - 1;
  *p++ = 'e';
  *p++ = x < 0 ? '-' : '+';
  if (x < 0) x = -x;
  if (x >= 100) *p++ = static_cast<char>('0' + x / 100), x %= 100;
  std::memcpy(p, kPairs + 2 * x, 2);
  return p + 2;
}
#endif

}  // namespace

char* write_shortest(char* out, double x) {
  x += 0.0;  // -0 as 0
#ifdef MBK_HAVE_DRAGONBOX
  if (x == 0) return *out = '0', out + 1;
  if (std::isfinite(x)) {
    const auto d = fmt::detail::dragonbox::to_decimal(x);
    if (char* end = write_decimal(out, x < 0, d.significand, d.exponent)) return end;
  }
#endif
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  return std::to_chars(out, out + kMaxDoubleChars, x).ptr;
#else  // e.g. GCC 9 (ROS Noetic): no std::to_chars for double; always 17 digits
  return out + std::snprintf(out, kMaxDoubleChars, "%.17g", x);
#endif
}

}  // namespace mbk
