// Memory the kernel has not yet given pages to (a fresh numpy array): the thread that will fill a
// range faults its pages in first, in one call (the kernel zeroes them then, on that thread),
// instead of one page fault at a time between the stores (doc/speed.md#python).
#pragma once

#include <cstddef>

namespace mbk {

// Faults in, writable, the pages holding bytes [begin, begin + bytes) (Linux's
// MADV_POPULATE_WRITE; elsewhere, or where the kernel refuses it, one byte of each page inside
// the range written with 0). Contents of bytes inside the range are undefined afterwards; bytes
// outside it are left as they are. For anonymous memory only: a file's mapping would be read in.
void fault_in(void* begin, std::size_t bytes);

}  // namespace mbk
