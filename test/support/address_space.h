// The process's address space, for tests that cap it (RLIMIT_AS) a little above what it holds.
#pragma once

#include <unistd.h>

#include <cstdio>

namespace mbk_test {

// This process's address space now, in bytes (/proc/self/statm's first field).
inline long address_space() {
  long pages = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  return pages * sysconf(_SC_PAGESIZE);
}

}  // namespace mbk_test
