// Copies with streaming (non-temporal) stores: each written cache line goes to memory without
// being read first and without evicting what the caches hold, for output far larger than the
// caches (the batch's arrays, offline/batch_kinematics.h; doc/speed.md#python). ROS-free.
#pragma once

#include <cstddef>

namespace mbk {

// `bytes` bytes from `from` to `to` (any alignment, not overlapping), as std::memcpy. The stores
// are weakly ordered: call stream_fence() before another thread reads `to`.
void stream_copy(void* to, const void* from, std::size_t bytes);

// Orders the streaming stores before every later store (sfence).
void stream_fence();

}  // namespace mbk
