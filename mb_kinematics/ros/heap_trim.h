// Freed heap memory back to the operating system (doc/speed.md "The node's load", RSS). Reading a
// robot_description builds XML trees that are freed once the model is made (about 60 MB for
// 10,000 links), but glibc keeps freed memory between live blocks in the process for good: the
// node's RSS would stay at its load-time peak. malloc_trim returns those pages.
#pragma once

#include <cstddef>  // defines __GLIBC__ with glibc
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace mbk_ros {

// Returns the heap's free pages to the system (glibc); elsewhere it does nothing.
inline void release_freed_heap() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

}  // namespace mbk_ros
