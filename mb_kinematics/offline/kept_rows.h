// The rows of a recording as RecordingBuilder's sink gives them (stamp, positions, velocities,
// given flags), kept in memory up to a bound in bytes for the passes after the first (mbk bag's
// streamed path). They are kept in blocks of fixed size: keeping a row never copies the rows
// before it, and the memory touched is the rows'. ROS-free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mbk {

class KeptRows {
 public:
  // nq coordinates per row; at most max_bytes of rows (their stamps, positions, velocities and
  // flags) are kept.
  KeptRows(int nq, std::size_t max_bytes);

  // Keeps a row (nq values each), in order; once a row would exceed the bound, forgets every row
  // and keeps none after (complete() is then false).
  void keep(double t, const double* position, const double* velocity, const std::uint8_t* given);
  // Every row offered is kept.
  bool complete() const { return complete_; }
  // The rows kept: none once the bound is passed.
  std::size_t rows() const { return rows_; }

  // Row r (< rows()) of those kept.
  struct Row {
    double t;
    const double *position, *velocity;
    const std::uint8_t* given;
  };
  Row row(std::size_t r) const;

 private:
  struct Block {
    std::vector<double> t, position, velocity;  // rows x nq
    std::vector<std::uint8_t> given;
  };
  void add_block();

  std::size_t nq_, most_, block_rows_;  // most_: the rows the bound holds
  std::size_t rows_ = 0;
  bool complete_ = true;
  std::vector<Block> blocks_;
};

}  // namespace mbk
