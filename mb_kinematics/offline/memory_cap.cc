#include "mb_kinematics/offline/memory_cap.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace mbk {

namespace {
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// AddressSanitizer reserves terabytes of address space for its shadow before main: an address
// space cap would fail its own mappings (scripts/test.sh --sanitize), so none is set there.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
}  // namespace

double default_memory_cap_gib() {
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double page = static_cast<double>(sysconf(_SC_PAGESIZE));
  return pages > 0 && page > 0 ? 0.9 * pages * page / kGiB : 0;
}

void cap_memory(double gib) {
  if (kAddressSanitizer || !(gib > 0) || !std::isfinite(gib)) return;  // size unknown: no cap
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0) return;
  const double bytes = gib * kGiB;
  const rlim_t wanted =
      bytes >= static_cast<double>(RLIM_INFINITY) ? RLIM_INFINITY : static_cast<rlim_t>(bytes);
  if (limit.rlim_max != RLIM_INFINITY && wanted > limit.rlim_max) return;  // a lower one holds
  limit.rlim_cur = wanted;
  if (setrlimit(RLIMIT_AS, &limit) != 0)
    throw std::invalid_argument(std::string("--max-memory: cannot set the limit (") +
                                std::strerror(errno) + ")");
}

std::string memory_cap_error(double gib) {
  char text[256];
  std::snprintf(text, sizeof text,
                "out of memory: the run needs more than --max-memory %.3g GiB of address space "
                "(default: 90 %% of this machine's memory); give a larger --max-memory or fewer "
                "--threads",
                gib);
  return text;
}

}  // namespace mbk
