#include "mb_kinematics/offline/kept_rows.h"

#include <algorithm>

namespace mbk {
namespace {

// The bytes of rows per block: large beside a block's four allocations, small beside the bound.
constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

std::size_t row_bytes(std::size_t nq) { return sizeof(double) * (1 + 2 * nq) + nq; }

}  // namespace

KeptRows::KeptRows(int nq, std::size_t max_bytes)
    : nq_(static_cast<std::size_t>(nq)),
      most_(max_bytes / row_bytes(nq_)),
      block_rows_(std::max<std::size_t>(1, kBlockBytes / row_bytes(nq_))) {}

void KeptRows::keep(double t, const double* position, const double* velocity,
                    const std::uint8_t* given) {
  if (!complete_) return;
  if (rows_ == most_) {
    complete_ = false;
    blocks_ = {};
    rows_ = 0;
    return;
  }
  if (rows_ % block_rows_ == 0) add_block();
  Block& b = blocks_.back();
  b.t.push_back(t);
  b.position.insert(b.position.end(), position, position + nq_);
  b.velocity.insert(b.velocity.end(), velocity, velocity + nq_);
  b.given.insert(b.given.end(), given, given + nq_);
  ++rows_;
}

KeptRows::Row KeptRows::row(std::size_t r) const {
  const Block& b = blocks_[r / block_rows_];
  const std::size_t i = r % block_rows_;
  return {b.t[i], b.position.data() + i * nq_, b.velocity.data() + i * nq_,
          b.given.data() + i * nq_};
}

void KeptRows::add_block() {
  blocks_.emplace_back();
  Block& b = blocks_.back();
  const std::size_t rows = std::min(block_rows_, most_ - rows_);
  b.t.reserve(rows), b.position.reserve(rows * nq_), b.velocity.reserve(rows * nq_);
  b.given.reserve(rows * nq_);
}

}  // namespace mbk
