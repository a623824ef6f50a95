// Copies with streaming (non-temporal) stores: each written cache line goes to memory without
// being read first and without evicting what the caches hold, for output far larger than the
// caches (the batch's arrays, offline/batch_kinematics.h; doc/speed.md#python). ROS-free.
#pragma once

#include <cstddef>

namespace mbk {

// `bytes` bytes from `from` to `to` (any alignment, not overlapping), as std::memcpy. The stores
// are weakly ordered: call stream_fence() before another thread reads `to`.
void stream_copy(void* to, const void* from, std::size_t bytes);

// A 64-byte line of the caller's array that one block written by stream_transpose8 ends inside:
// its first `count` numbers, held until the next block, which starts where this one ended,
// completes the line, so that it is written once and whole.
struct HeldLine {
  double* at = nullptr;  // the line (64-byte aligned); null: none held
  std::size_t count = 0;
  double numbers[8];
};

// The transpose of the n x 8 matrix a (row e: a + 8 e) into b (row l: b + l n), b's lines
// written with streaming stores, each once and whole: eight samples' rows of a field from its
// numbers in DoubleLanes<8> (a[8 e + l]: sample l's number e), as the batch streams them
// (offline/batch_kinematics.cc). A line b ends inside is held in `held` (and written by the next
// call if b follows on, or by write_held); a first line b shares with a line held is completed
// and written, one it shares with anything else written with ordinary stores, only to b's
// numbers. On CPUs with AVX-512F, for n >= 8 and b on a double's boundary, in registers,
// straight from a to memory; else one number at a time with ordinary stores (b at any address).
// Call stream_fence() before another thread reads b.
void stream_transpose8(const double* a, std::size_t n, double* b, HeldLine& held);

// The numbers `held` holds, written with ordinary stores; then it holds none.
void write_held(HeldLine& held);

// Orders the streaming stores before every later store (sfence).
void stream_fence();

}  // namespace mbk
