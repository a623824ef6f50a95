// mbk bag's memory cap (--max-memory): the process's address space is limited (RLIMIT_AS) so
// that an allocation beyond the cap fails, as std::bad_alloc, and the run ends with one line
// naming the option, instead of the kernel's out-of-memory killer ending it (or the machine
// swapping). The cap counts address space, not resident memory: the libraries and the threads'
// stacks and malloc arenas take about 200 MB of it beside what the run allocates. ROS-free.
#pragma once

#include <string>

namespace mbk {

// The default: 90 % of the machine's physical memory, in GiB.
double default_memory_cap_gib();
// Limits this process (and the children it starts) to `gib` GiB of address space.
void cap_memory(double gib);
// The one-line error for an allocation the cap refused.
std::string memory_cap_error(double gib);

}  // namespace mbk
