#include "mb_kinematics/offline/stream_copy.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace mbk {
namespace {

// stream_transpose8 with ordinary stores, b at any address (numpy's arrays need not be on a
// double's boundary).
void transpose8(const double* a, std::size_t n, double* b, HeldLine& held) {
  write_held(held);
  for (std::size_t l = 0; l < 8; ++l)
    for (std::size_t e = 0; e < n; ++e) std::memcpy(b + l * n + e, a + e * 8 + l, sizeof(double));
}

}  // namespace

void write_held(HeldLine& held) {
  if (held.at) std::copy(held.numbers, held.numbers + held.count, held.at);
  held.at = nullptr;
}

#if defined(__x86_64__)
namespace {

std::uintptr_t address(const char* p) { return reinterpret_cast<std::uintptr_t>(p); }

// Each copies from a boundary of its size of `to` and returns the bytes it copied (a multiple of
// its size, at most `bytes`); the pointers are locals, which the stores cannot be taken to alias.
std::size_t stream4(char* to, const char* from, std::size_t bytes) {
  std::size_t done = 0;
  for (; done + 4 <= bytes; done += 4) {
    int word;
    std::memcpy(&word, from + done, 4);
    _mm_stream_si32(reinterpret_cast<int*>(to + done), word);
  }
  return done;
}

std::size_t stream16(char* to, const char* from, std::size_t bytes) {
  std::size_t done = 0;
  for (; done + 16 <= bytes; done += 16)
    _mm_stream_si128(reinterpret_cast<__m128i*>(to + done),
                     _mm_loadu_si128(reinterpret_cast<const __m128i*>(from + done)));
  return done;
}

// Half the store instructions of SSE2's, and a batch 4-8 % faster (doc/speed.md#python).
__attribute__((target("avx"))) std::size_t stream32_avx(char* to, const char* from,
                                                        std::size_t bytes) {
  std::size_t done = 0;
  for (; done + 32 <= bytes; done += 32)
    _mm256_stream_si256(reinterpret_cast<__m256i*>(to + done),
                        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(from + done)));
  return done;
}

bool has_avx() {
  static const bool avx = __builtin_cpu_supports("avx");
  return avx;
}

bool has_avx512f() {
  static const bool avx512f = __builtin_cpu_supports("avx512f");
  return avx512f;
}

// c[l] = (r[0][l], ..., r[7][l]): the 8 x 8 block r transposed, in 24 permutes. (GCC 12's
// unpack and shuffle intrinsics start from _mm512_undefined_pd, which -Wuninitialized takes for
// a read of an uninitialized variable: GCC bug 105593, fixed in GCC 13.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
__attribute__((target("avx512f"))) void transpose8x8(const __m512d r[8], __m512d c[8]) {
  const __m512i low = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
  const __m512i high = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  __m512d t[8], u[8];
  for (int i = 0; i < 8; i += 2) {  // t[i] = r[i][0] r[i+1][0] r[i][2] ..., t[i+1]: the odd ones
    t[i] = _mm512_unpacklo_pd(r[i], r[i + 1]);
    t[i + 1] = _mm512_unpackhi_pd(r[i], r[i + 1]);
  }
  for (int i = 0; i < 8; i += 4)  // u[i + d]: rows i..i+3 of columns d and d + 4
    for (int d = 0; d < 2; ++d) {
      u[i + d] = _mm512_permutex2var_pd(t[i + d], low, t[i + d + 2]);
      u[i + d + 2] = _mm512_permutex2var_pd(t[i + d], high, t[i + d + 2]);
    }
  for (int d = 0; d < 4; ++d) {
    c[d] = _mm512_shuffle_f64x2(u[d], u[d + 4], 0x44);
    c[d + 4] = _mm512_shuffle_f64x2(u[d], u[d + 4], 0xEE);
  }
}
#pragma GCC diagnostic pop

// stream_transpose8 on AVX-512F. Row l of b starts offset[l] numbers into a 64-byte line; its line
// m (m = 0, 1, ...) is numbers 8 m - offset[l] .. 8 m - offset[l] + 7 of the row, which are the
// last offset[l] numbers of column l's block m - 1 of a and the first 8 - offset[l] of its block
// m, joined by one permute. The first and last lines of each row, which it shares with the rows
// before and after it, are kept and joined at the end.
__attribute__((target("avx512f"))) void stream_transpose8_avx512(const double* a, std::size_t n,
                                                                 double* b, HeldLine& held) {
  alignas(64) static const long long kJoin[8][8] = {
      {8, 9, 10, 11, 12, 13, 14, 15}, {7, 8, 9, 10, 11, 12, 13, 14}, {6, 7, 8, 9, 10, 11, 12, 13},
      {5, 6, 7, 8, 9, 10, 11, 12},    {4, 5, 6, 7, 8, 9, 10, 11},    {3, 4, 5, 6, 7, 8, 9, 10},
      {2, 3, 4, 5, 6, 7, 8, 9},       {1, 2, 3, 4, 5, 6, 7, 8}};
  const std::size_t o = address(reinterpret_cast<char*>(b)) / 8 % 8;
  double* const lines = b - o;  // 64-byte aligned
  std::size_t offset[8];
  double* first[8];  // row l's first line
  for (std::size_t l = 0; l < 8; ++l) {
    offset[l] = (o + l * n) % 8;
    first[l] = lines + (o + l * n) / 8 * 8;
  }
  alignas(64) double head[8][8], tail[8][8];  // each row's first and last line, if shared
  __m512d before[8] = {};                     // each column's block m - 1
  const std::size_t blocks = (n + 7) / 8;
  for (std::size_t m = 0; m <= blocks; ++m) {
    __m512d r[8], c[8];
    for (std::size_t i = 0; i < 8; ++i)
      r[i] = 8 * m + i < n ? _mm512_loadu_pd(a + (8 * m + i) * 8) : _mm512_setzero_pd();
    transpose8x8(r, c);
    for (std::size_t l = 0; l < 8; ++l) {
      const auto start =
          static_cast<std::ptrdiff_t>(8 * m) - static_cast<std::ptrdiff_t>(offset[l]);
      const auto rows = static_cast<std::ptrdiff_t>(n);
      if (start < rows) {
        const __m512d line =
            _mm512_permutex2var_pd(before[l], _mm512_load_si512(kJoin[offset[l]]), c[l]);
        if (start < 0)
          _mm512_store_pd(head[l], line);
        else if (start + 8 > rows)
          _mm512_store_pd(tail[l], line);
        else
          _mm512_stream_pd(first[l] + 8 * m, line);
      }
      before[l] = c[l];
    }
  }
  // Row l - 1's last line is row l's first (n >= 8).
  for (std::size_t l = 1; l < 8; ++l)
    if (offset[l] > 0)
      _mm512_stream_pd(first[l],
                       _mm512_mask_blend_pd(static_cast<__mmask8>((1u << offset[l]) - 1),
                                            _mm512_load_pd(head[l]), _mm512_load_pd(tail[l - 1])));
  // b's first line: completing the line held, or shared with numbers before b; its last line.
  if (held.at && (o == 0 || held.at != first[0] || held.count != o)) write_held(held);
  if (o == 0) return;
  const __mmask8 before_b = static_cast<__mmask8>((1u << o) - 1);
  if (held.at) {
    _mm512_stream_pd(first[0], _mm512_mask_blend_pd(before_b, _mm512_load_pd(head[0]),
                                                    _mm512_loadu_pd(held.numbers)));
  } else {
    _mm512_mask_storeu_pd(first[0], static_cast<__mmask8>(~before_b), _mm512_load_pd(head[0]));
  }
  held.at = lines + (o + 8 * n) / 8 * 8;
  held.count = o;
  _mm512_storeu_pd(held.numbers, _mm512_load_pd(tail[7]));
}

}  // namespace

void stream_copy(void* destination, const void* source, std::size_t bytes) {
  char* to = static_cast<char*>(destination);
  const char* from = static_cast<const char*>(source);
  const auto advance = [&](std::size_t done) { to += done, from += done, bytes -= done; };
  // Ordinary stores up to a 4-byte boundary (the arrays of doubles and floats start on one), then
  // 4-byte streaming stores up to a 16-byte one (and 16-byte ones up to a 32-byte one for AVX).
  for (; bytes > 0 && address(to) % 4 != 0; --bytes) *to++ = *from++;
  advance(stream4(to, from, std::min(bytes & ~std::size_t{3}, (16 - address(to) % 16) % 16)));
  if (has_avx()) {
    if (address(to) % 32 != 0) advance(stream16(to, from, std::min(bytes, std::size_t{16})));
    advance(stream32_avx(to, from, bytes));
  }
  advance(stream16(to, from, bytes));
  advance(stream4(to, from, bytes));
  std::memcpy(to, from, bytes);
}

void stream_fence() { _mm_sfence(); }

void stream_transpose8(const double* a, std::size_t n, double* b, HeldLine& held) {
  if (has_avx512f() && n >= 8 && address(reinterpret_cast<char*>(b)) % sizeof(double) == 0)
    return stream_transpose8_avx512(a, n, b, held);
  transpose8(a, n, b, held);
}

#else  // no streaming stores: ordinary ones

void stream_copy(void* to, const void* from, std::size_t bytes) { std::memcpy(to, from, bytes); }

void stream_fence() {}

void stream_transpose8(const double* a, std::size_t n, double* b, HeldLine& held) {
  transpose8(a, n, b, held);
}

#endif

}  // namespace mbk
