// Large memory blocks for output arrays (the Python module's fresh arrays, doc/python.md), kept
// when their arrays are released and handed out again: a loop of calls that drops each call's
// arrays before the next writes into memory the process already holds, instead of paying the
// kernel's page faults and zeroing for every call (doc/speed.md#python). A request takes a kept
// range of its size, or the front of the smallest larger one (so a chunk's arrays fit in the
// blocks of an earlier, larger call's); released ranges next to each other are joined again. The
// bytes kept never exceed the most the process held in blocks at once, and stay resident until
// reused or release()d (marking them MADV_FREE instead made every write into them slower:
// doc/speed.md). Thread-safe. ROS-free.
#pragma once

#include <cstddef>
#include <map>
#include <mutex>

namespace mbk {

class RetainedBlocks {
 public:
  // The process's blocks, shared by every caller.
  static RetainedBlocks& shared();
  // A block of at least `bytes` (page-aligned): from a kept range of at least the same rounded
  // size (the smallest such), or a new mapping (transparent huge pages asked for; first touched
  // by whoever writes it). Throws std::bad_alloc when the kernel has no memory for it.
  void* take(std::size_t bytes);
  // A block from take(bytes) back: kept (joined with the kept ranges beside it), or unmapped
  // when keeping it would exceed the cap.
  void give(void* block, std::size_t bytes);
  // Every kept range back to the kernel; returns their bytes.
  std::size_t release();
  std::size_t kept_bytes() const;
  // How many separate ranges are kept (adjacent released blocks count once).
  std::size_t kept_ranges() const;
  ~RetainedBlocks();

 private:
  // Both called with mutex_ held. take_kept: nullptr when no kept range holds `size`.
  void* take_kept(std::size_t size);
  void keep(char* block, std::size_t size);

  mutable std::mutex mutex_;
  std::map<char*, std::size_t> kept_;  // start -> bytes; ranges that neither touch nor overlap
  std::size_t kept_bytes_ = 0;
  std::size_t in_use_ = 0, most_in_use_ = 0;
};

}  // namespace mbk
