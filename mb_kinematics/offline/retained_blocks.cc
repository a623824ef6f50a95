#include "mb_kinematics/offline/retained_blocks.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <new>
#include <utility>

namespace mbk {
namespace {

std::size_t rounded(std::size_t bytes) {
  const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return (std::max<std::size_t>(bytes, 1) + page - 1) / page * page;
}

}  // namespace

RetainedBlocks& RetainedBlocks::shared() {
  static RetainedBlocks* blocks = new RetainedBlocks;  // outlives every array at exit
  return *blocks;
}

void* RetainedBlocks::take(std::size_t bytes) {
  const std::size_t size = rounded(bytes);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    in_use_ += size;
    most_in_use_ = std::max(most_in_use_, in_use_);
    const auto kept = kept_.find(size);
    if (kept != kept_.end()) {
      void* block = kept->second;
      kept_.erase(kept);
      kept_bytes_ -= size;
      return block;
    }
  }
  void* block = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (block == MAP_FAILED) {
    const std::lock_guard<std::mutex> lock(mutex_);
    in_use_ -= size;
    throw std::bad_alloc();
  }
#ifdef MADV_HUGEPAGE
  madvise(block, size, MADV_HUGEPAGE);
#endif
  return block;
}

void RetainedBlocks::give(void* block, std::size_t bytes) {
  const std::size_t size = rounded(bytes);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    in_use_ -= size;
    if (kept_bytes_ + size <= most_in_use_) {
      kept_.emplace(size, block);
      kept_bytes_ += size;
      return;
    }
  }
  munmap(block, size);
}

std::size_t RetainedBlocks::release() {
  std::multimap<std::size_t, void*> kept;
  std::size_t bytes = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    kept.swap(kept_);
    std::swap(bytes, kept_bytes_);
  }
  for (const auto& [size, block] : kept) munmap(block, size);
  return bytes;
}

std::size_t RetainedBlocks::kept_bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return kept_bytes_;
}

RetainedBlocks::~RetainedBlocks() {
  for (const auto& [size, block] : kept_) munmap(block, size);
}

}  // namespace mbk
