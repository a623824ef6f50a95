// A copy that bypasses the caches on its way to memory (non-temporal stores on x86-64; memcpy
// elsewhere): the destination's lines are not read first (no read-for-ownership) and do not
// evict what the computation still uses. For outputs far larger than the caches that are
// written once (offline/batch_kinematics.h); call stream_fence() once after the last copy of a
// thread, before another thread reads what it wrote. ROS-free.
#pragma once

#include <cstddef>

namespace mbk {

// Copies `bytes` (a multiple of 4; `to` and `from` 4-byte aligned) from `from` to `to`.
void stream_copy(void* to, const void* from, std::size_t bytes);
void stream_fence();

}  // namespace mbk
