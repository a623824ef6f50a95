#include "mb_kinematics/offline/stream_copy.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace mbk {

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

#else  // no streaming stores: ordinary ones

void stream_copy(void* to, const void* from, std::size_t bytes) { std::memcpy(to, from, bytes); }

void stream_fence() {}

#endif

}  // namespace mbk
