#include "mb_kinematics/io/number_format.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

// fmt header-only (also where a build, e.g. test/fuzz, names no fmt library): Dragonbox compiled
// here, with its full table of powers of ten (10 kB; 40 % fewer instructions than the compressed).
#if __has_include(<fmt/format.h>)
#ifndef FMT_HEADER_ONLY
#define FMT_HEADER_ONLY 1
#endif
#define FMT_USE_FULL_CACHE_DRAGONBOX 1
#include <fmt/format.h>
#endif
#if defined(FMT_VERSION) && FMT_VERSION >= 80000
#define MBK_HAVE_DRAGONBOX 1  // with the layout below, less than half std::to_chars's instructions
#endif

namespace mbk {

namespace {

#ifdef MBK_HAVE_DRAGONBOX
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// 10^0 ... 10^19.
constexpr std::array<uint64_t, 20> powers_of_ten() {
  std::array<uint64_t, 20> p{};
  uint64_t x = 1;
  for (uint64_t& v : p) v = x, x *= 10;
  return p;
}

// Decimal digits of m > 0.
int digit_count(uint64_t m) {
  static constexpr std::array<uint64_t, 20> kPow10 = powers_of_ten();
  const int t = ((64 - __builtin_clzll(m)) * 1233) >> 12;  // 1233/4096 ~ log10(2)
  return t + (m >= kPow10[t]);
}

// Room for write_digits: 17 digits and the 17 bytes a copy may read after the first of them.
constexpr int kDigitsRoom = 34;

// n < 10^8 as 8 digits at out: n / 10^6 in 57-bit fixed point, two digits per product (exact for
// every n < 10^8: the rounding error stays below 1/100 after three products by 100).
[[gnu::always_inline]] inline void write8(char* out, uint32_t n) {
  constexpr uint64_t kScale = ((uint64_t{1} << 57) + 999999) / 1000000;  // ceil(2^57 / 10^6)
  constexpr uint64_t kMask = (uint64_t{1} << 57) - 1;
  uint64_t t = n * kScale;
  std::memcpy(out, kPairs + 2 * (t >> 57), 2);
  t = (t & kMask) * 100;
  std::memcpy(out + 2, kPairs + 2 * (t >> 57), 2);
  t = (t & kMask) * 100;
  std::memcpy(out + 4, kPairs + 2 * (t >> 57), 2);
  t = (t & kMask) * 100;
  std::memcpy(out + 6, kPairs + 2 * (t >> 57), 2);
}

// The digits of m < 10^17 as 17 characters at `digits` (leading zeros); returns the first of
// its n = digit_count(m) digits. Reads of 17 bytes from there stay inside the buffer.
const char* write_digits(char* digits, uint64_t m, int n) {
  const uint64_t high = m / 100000000;
  digits[0] = static_cast<char>('0' + high / 100000000);
  write8(digits + 1, static_cast<uint32_t>(high % 100000000));
  write8(digits + 9, static_cast<uint32_t>(m % 100000000));
  return digits + 17 - n;
}

// m * 10^e (m without trailing zeros, n digits) as std::to_chars(first, last, x) writes it:
// fixed when not longer than scientific (libstdc++'s bounds), scientific as "d.ddde+XX".
// nullptr for a whole number too large to be exact from m and e (std::to_chars prints those).
// Copies are of fixed sizes (17 digits, 5 zeros): what follows the returned end is scratch.
char* write_decimal(char* out, bool negative, uint64_t m, int e) {
  if (negative) *out++ = '-';
  const int n = digit_count(m);
  const int lower = n == 1 ? -3 : -(n + 3), upper = n == 1 ? 4 : 5;
  char buffer[kDigitsRoom] = {};
  const char* digits = write_digits(buffer, m, n);
  if (e >= lower && e <= upper) {
    if (e >= 0) {
      if ((63 - __builtin_clzll(m)) + (e * 10 + 2) / 3 >= 50) return nullptr;
      std::memcpy(out, digits, 17);
      std::memcpy(out + n, "00000", 5);
      return out + n + e;
    }
    if (n <= -e) {  // below 1: "0.00ddd", at most 3 zeros
      const int zeros = -e - n;
      std::memcpy(out, "0.000", 5);
      std::memcpy(out + 2 + zeros, digits, 17);
      return out + 2 + zeros + n;
    }
    const int whole = n + e;  // "ddd.ddd"
    std::memcpy(out, digits, 17);
    std::memcpy(out + whole + 1, digits + whole, 17);
    out[whole] = '.';
    return out + n + 1;
  }
  out[0] = digits[0];  // "d.ddde+XX"
  out[1] = '.';
  std::memcpy(out + 2, digits + 1, 16);
  char* p = out + (n > 1 ? n + 1 : 1);
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
#else  // e.g. GCC 9 (ROS Noetic): no std::to_chars for double
  int n = 0;
  for (int digits = 15; digits <= 17; ++digits) {
    n = std::snprintf(out, kMaxDoubleChars, "%.*g", digits, x);
    if (std::strtod(out, nullptr) == x) break;
  }
  return out + n;
#endif
}

std::string format_double(double x) {
  char text[kMaxDoubleChars];
  return std::string(text, write_shortest(text, x));
}

}  // namespace mbk
