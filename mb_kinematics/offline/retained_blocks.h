// Large memory blocks for output arrays (the Python module's fresh arrays, doc/python.md), kept
// when their arrays are released and handed out again: a loop of calls that drops each call's
// arrays before the next writes into memory the process already holds, instead of paying the
// kernel's page faults and zeroing for every call (doc/speed.md#python). The blocks kept never
// exceed the most the process held in blocks at once, and stay resident until reused or
// release()d (marking them MADV_FREE instead made every write into them slower: doc/speed.md).
// Thread-safe. ROS-free.
#pragma once

#include <cstddef>
#include <map>
#include <mutex>

namespace mbk {

class RetainedBlocks {
 public:
  // The process's blocks, shared by every caller.
  static RetainedBlocks& shared();
  // A block of at least `bytes` (page-aligned): a kept one of the same rounded size, or a new
  // mapping (transparent huge pages asked for; first touched by whoever writes it). Throws
  // std::bad_alloc when the kernel has no memory for it.
  void* take(std::size_t bytes);
  // A block from take(bytes) back: kept, or unmapped when keeping it would exceed the cap.
  void give(void* block, std::size_t bytes);
  // Every kept block back to the kernel; returns their bytes.
  std::size_t release();
  std::size_t kept_bytes() const;
  ~RetainedBlocks();

 private:
  mutable std::mutex mutex_;
  std::multimap<std::size_t, void*> kept_;  // rounded size -> block
  std::size_t kept_bytes_ = 0;
  std::size_t in_use_ = 0, most_in_use_ = 0;
};

}  // namespace mbk
