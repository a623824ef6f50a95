// Copies with streaming (non-temporal) stores: each written cache line goes to memory without
// being read first and without evicting what the caches hold, for output far larger than the
// caches (the batch's arrays, offline/batch_kinematics.h; doc/speed.md#python). ROS-free.
#pragma once

#include <cstddef>

namespace mbk {

// `bytes` bytes from `from` to `to` (any alignment, not overlapping), as std::memcpy. The stores
// are weakly ordered: call stream_fence() before another thread reads `to`.
void stream_copy(void* to, const void* from, std::size_t bytes);

// The transpose of the n x 8 matrix a (row e: a + 8 e) into b (row l: b + l n), n >= 8, b's lines
// written with streaming stores, each once and whole, but for the two it may share with what is
// before and after it (ordinary stores, only to b's numbers): eight samples' rows of a field from
// its numbers in DoubleLanes<8> (a[8 e + l]: sample l's number e), as the batch streams them
// (offline/batch_kinematics.cc). On CPUs with AVX-512F in registers, straight from a to memory;
// elsewhere one number at a time. Call stream_fence() before another thread reads b.
void stream_transpose8(const double* a, std::size_t n, double* b);

// Orders the streaming stores before every later store (sfence).
void stream_fence();

}  // namespace mbk
