#include "mb_kinematics/io/number_format.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace mbk {

namespace {

// A decimal d1d2...dn 10^(exponent - n + 1): n = count digits, the first at 10^exponent.
struct Decimal {
  uint32_t digits;
  int count, exponent;
};

template <typename T, int N>
constexpr std::array<T, N> powers(T base) {
  std::array<T, N> p{};
  T x = 1;
  for (T& v : p) v = x, x *= base;
  return p;
}
constexpr std::array<double, 23> kExactPowers = powers<double, 23>(10);  // 5^22 < 2^53: exact
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// The digits of n, count of them (leading zeros if n has fewer), at out, two at a time from the
// last.
char* write_uint(char* out, uint32_t n, int count) {
  char* at = out + count;
  for (; at - out >= 2; n /= 100) at -= 2, std::memcpy(at, kPairs + 2 * (n % 100), 2);
  if (at > out) *out = static_cast<char>('0' + n % 10);
  return out + count;
}

// e+XX, e-XX or e+XXX: the exponent at least two digits, as printf's %e writes it.
char* write_exponent(char* out, int e) {
  *out++ = 'e', *out++ = e < 0 ? '-' : '+';
  int ae = std::abs(e);
  if (ae >= 100) *out++ = static_cast<char>('0' + ae / 100), ae %= 100;
  std::memcpy(out, kPairs + 2 * ae, 2);
  return out + 2;
}

// v without its trailing zeros (%g without '#', and std::to_chars, write none).
Decimal trimmed(uint32_t digits, int count, int exponent) {
  while (count > 1 && digits % 10 == 0) digits /= 10, --count;
  return {digits, count, exponent};
}

// v as printf's %e ("d.ddde+XX", the exponent at least two digits) or %f writes it.
char* lay_out(char* out, const Decimal& v, bool scientific) {
  const int n = v.count, e = v.exponent;
  if (scientific) {
    write_uint(out + 1, v.digits, n);
    out[0] = out[1];
    out += n > 1 ? (out[1] = '.', n + 1) : 1;
    return write_exponent(out, e);
  }
  if (e < 0) {  // 0.000ddd
    *out++ = '0', *out++ = '.';
    out = std::fill_n(out, -e - 1, '0');
    return write_uint(out, v.digits, n);
  }
  if (n <= e + 1) return std::fill_n(write_uint(out, v.digits, n), e + 1 - n, '0');
  write_uint(out + 1, v.digits, n);  // ddd.ddd
  for (int i = 0; i <= e; ++i) out[i] = out[i + 1];
  out[e + 1] = '.';
  return out + n + 1;
}

// |x|'s digits rounded to p <= kFastPrecision significant digits as printf rounds them, from
// double arithmetic: |x| 10^k (10^|k| an exact double) is one correctly rounded product in
// [10^(p - 1), 10^p), within 10^p 2^-53 of the exact value, so rounding it to an integer is
// printf's rounding except within that distance of a half: false there, for x = 0, not finite,
// or 10^|k| beyond 10^22.
constexpr int kFastPrecision = 9;
bool rounded_decimal(double x, int p, Decimal& out) {
  if (!std::isfinite(x) || x == 0) return false;
  const double ax = std::abs(x), low = kExactPowers[p - 1], high = kExactPowers[p];
  const auto scaled = [ax](int k) {  // ax 10^k, or -1
    if (std::abs(k) >= static_cast<int>(kExactPowers.size())) return -1.0;
    return k >= 0 ? ax * kExactPowers[k] : ax / kExactPowers[-k];
  };
  uint64_t bits;
  std::memcpy(&bits, &ax, sizeof bits);
  int e = ((static_cast<int>(bits >> 52) - 1023) * 1233) >> 12;  // %e's exponent, or one below
  double y = scaled(p - 1 - e);
  if (y >= 0 && y < low) y = scaled(p - 1 - --e);
  if (y >= high) y = scaled(p - 1 - ++e);
  if (y < low || y >= high) return false;
  const double whole = std::floor(y), fraction = y - whole;
  if (std::abs(fraction - 0.5) < 1e-6) return false;  // too near a half to round here
  uint32_t digits = static_cast<uint32_t>(whole) + (fraction > 0.5);
  if (digits == static_cast<uint32_t>(high)) digits /= 10, ++e;
  out = trimmed(digits, p, e);
  return true;
}

}  // namespace

char* write_shortest(char* out, double x) {
  if (x == 0) {  // 0 and -0 as "0", without the conversion (5 % of the tidy CSV's numbers)
    *out = '0';
    return out + 1;
  }
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
  Decimal v;
  if (precision >= 1 && precision <= kFastPrecision && rounded_decimal(x, precision, v)) {
    if (x < 0) *out++ = '-';
    return lay_out(out, v, v.exponent < -4 || v.exponent >= precision);
  }
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

namespace mbk {

char* write_stamp(char* out, double origin, double t) {
  const double whole = std::floor(t);
  double seconds = origin + whole;                 // whole numbers: exact below 2^53
  long long ns = std::llround((t - whole) * 1e9);  // t - whole is exact
  if (ns == 1000000000) seconds += 1, ns = 0;
  if (!std::isfinite(t) || !(std::abs(seconds) < 9e15))  // beyond whole seconds and nanoseconds
    return out + std::snprintf(out, kMaxStampChars, "%.9f", origin + t);
  const bool negative = seconds < 0;
  if (negative && ns > 0) seconds += 1, ns = 1000000000 - ns;  // -1 + 0.75 is -0.25
  return out + std::snprintf(out, kMaxStampChars, "%s%lld.%09lld", negative ? "-" : "",
                             static_cast<long long>(std::abs(seconds)), ns);
}

double written_stamp(double origin, double t) {
  char text[kMaxStampChars];
  write_stamp(text, origin, t);
  return std::strtod(text, nullptr);
}

}  // namespace mbk
