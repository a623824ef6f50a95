#include "mb_kinematics/offline/fresh_pages.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace mbk {
namespace {

constexpr std::uintptr_t kPage = 4096;

// One store per page inside the range: each page's first fault happens here.
void touch(char* begin, std::size_t bytes) {
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(begin) + bytes;
  for (std::uintptr_t at = reinterpret_cast<std::uintptr_t>(begin); at < end;
       at = (at | (kPage - 1)) + 1)
    *reinterpret_cast<volatile char*>(at) = 0;
}

}  // namespace

void fault_in(void* begin, std::size_t bytes) {
  if (bytes == 0) return;
  char* const first = static_cast<char*>(begin);
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  // The pages holding the range: the first and last also hold bytes of the range, so they are
  // mapped; populating does not change what they hold.
  const std::uintptr_t from = reinterpret_cast<std::uintptr_t>(first) & ~(kPage - 1);
  const std::uintptr_t to =
      (reinterpret_cast<std::uintptr_t>(first + bytes) + kPage - 1) & ~(kPage - 1);
  if (madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE) == 0) return;
#endif
  touch(first, bytes);
}

}  // namespace mbk
