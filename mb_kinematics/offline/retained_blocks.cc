#include "mb_kinematics/offline/retained_blocks.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <iterator>
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
    if (void* block = take_kept(size)) return block;
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

void* RetainedBlocks::take_kept(std::size_t size) {
  auto best = kept_.end();
  for (auto range = kept_.begin(); range != kept_.end(); ++range)
    if (range->second >= size && (best == kept_.end() || range->second < best->second))
      best = range;
  if (best == kept_.end()) return nullptr;
  char* block = best->first;
  const std::size_t rest = best->second - size;
  kept_.erase(best);
  if (rest > 0) kept_.emplace(block + size, rest);
  kept_bytes_ -= size;
  return block;
}

void RetainedBlocks::give(void* block, std::size_t bytes) {
  const std::size_t size = rounded(bytes);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    in_use_ -= size;
    if (kept_bytes_ + size <= most_in_use_) {
      keep(static_cast<char*>(block), size);
      return;
    }
  }
  munmap(block, size);
}

void RetainedBlocks::keep(char* block, std::size_t size) {
  kept_bytes_ += size;
  auto next = kept_.lower_bound(block);
  if (next != kept_.begin()) {
    const auto before = std::prev(next);
    if (before->first + before->second == block) {  // joined to the range before it
      block = before->first;
      size += before->second;
      kept_.erase(before);
    }
  }
  if (next != kept_.end() && block + size == next->first) {  // and to the one after it
    size += next->second;
    next = kept_.erase(next);
  }
  kept_.emplace_hint(next, block, size);
}

std::size_t RetainedBlocks::release() {
  std::map<char*, std::size_t> kept;
  std::size_t bytes = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    kept.swap(kept_);
    std::swap(bytes, kept_bytes_);
  }
  for (const auto& [block, size] : kept) munmap(block, size);
  return bytes;
}

std::size_t RetainedBlocks::kept_bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return kept_bytes_;
}

std::size_t RetainedBlocks::kept_ranges() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return kept_.size();
}

RetainedBlocks::~RetainedBlocks() {
  for (const auto& [block, size] : kept_) munmap(block, size);
}

}  // namespace mbk
