#include "mb_kinematics/offline/stream_copy.h"

#include <cstdint>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace mbk {

#if defined(__x86_64__)
namespace {

std::uintptr_t address(const char* p) { return reinterpret_cast<std::uintptr_t>(p); }

void stream4(char*& to, const char*& from, std::size_t& bytes) {
  int word;
  std::memcpy(&word, from, 4);
  _mm_stream_si32(reinterpret_cast<int*>(to), word);
  to += 4, from += 4, bytes -= 4;
}

void stream16(char*& to, const char*& from, std::size_t& bytes) {
  _mm_stream_si128(reinterpret_cast<__m128i*>(to),
                   _mm_loadu_si128(reinterpret_cast<const __m128i*>(from)));
  to += 16, from += 16, bytes -= 16;
}

// From a 32-byte boundary of `to`: half the store instructions of SSE2's, and a batch 4-8 %
// faster (doc/speed.md#python).
__attribute__((target("avx"))) void stream32_avx(char*& to, const char*& from, std::size_t& bytes) {
  for (; bytes >= 32; to += 32, from += 32, bytes -= 32)
    _mm256_stream_si256(reinterpret_cast<__m256i*>(to),
                        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(from)));
}

bool has_avx() {
  static const bool avx = __builtin_cpu_supports("avx");
  return avx;
}

}  // namespace

void stream_copy(void* destination, const void* source, std::size_t bytes) {
  char* to = static_cast<char*>(destination);
  const char* from = static_cast<const char*>(source);
  // Ordinary stores up to a 4-byte boundary (the arrays of doubles and floats start on one), then
  // 4-byte streaming stores up to a 16-byte one.
  for (; bytes > 0 && address(to) % 4 != 0; --bytes) *to++ = *from++;
  while (bytes >= 4 && address(to) % 16 != 0) stream4(to, from, bytes);
  if (has_avx()) {
    if (bytes >= 16 && address(to) % 32 != 0) stream16(to, from, bytes);
    stream32_avx(to, from, bytes);
  }
  while (bytes >= 16) stream16(to, from, bytes);
  while (bytes >= 4) stream4(to, from, bytes);
  std::memcpy(to, from, bytes);
}

void stream_fence() { _mm_sfence(); }

#else  // no streaming stores: ordinary ones

void stream_copy(void* to, const void* from, std::size_t bytes) { std::memcpy(to, from, bytes); }

void stream_fence() {}

#endif

}  // namespace mbk
