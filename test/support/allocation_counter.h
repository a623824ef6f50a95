// Counting replacements of global operator new / new[] (calls and bytes) and, on glibc, of
// malloc (Eigen's dynamic storage and other C code allocate with malloc), for the "no allocation
// per sample" tests and a memory bound. Include it in exactly one source file of a test
// executable: it defines the replaceable functions.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

std::atomic<long> g_news{0};
std::atomic<long> g_new_bytes{0};
std::atomic<long> g_mallocs{0};

void* counted_new(std::size_t size) {
  ++g_news;
  g_new_bytes += static_cast<long>(size);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}

void* counted_aligned_new(std::size_t size, std::align_val_t align) {
  ++g_news;
  g_new_bytes += static_cast<long>(size);
  const std::size_t a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return counted_new(size); }
void* operator new[](std::size_t size) { return counted_new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted_new(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void* operator new(std::size_t size, std::align_val_t align) {
  return counted_aligned_new(size, align);
}
void* operator new[](std::size_t size, std::align_val_t align) {
  return counted_aligned_new(size, align);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

// glibc lets a program interpose malloc; forward to its implementation after counting. Not under
// sanitizers, which interpose malloc themselves.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define MBK_COUNT_MALLOC 1
#else
#define MBK_COUNT_MALLOC 0
#endif

#if MBK_COUNT_MALLOC
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t n, std::size_t size);
extern "C" void* __libc_realloc(void* p, std::size_t size);
extern "C" void* malloc(std::size_t size) {
  ++g_mallocs;
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t n, std::size_t size) {
  ++g_mallocs;
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, std::size_t size) {
  ++g_mallocs;
  return __libc_realloc(p, size);
}
#endif

namespace mbk_test {

struct AllocationCounts {
  long news, mallocs;
  long new_bytes;  // asked of operator new and new[]
};
inline AllocationCounts allocation_counts() {
  return {g_news.load(), g_mallocs.load(), g_new_bytes.load()};
}

}  // namespace mbk_test
