// stream_copy (offline/stream_copy.h): the bytes of std::memcpy, at every alignment of either
// end and every length up to past a few 32-byte blocks, and nothing outside them touched.
#include "mb_kinematics/offline/stream_copy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

TEST(StreamCopy, TheBytesOfMemcpyAtEveryAlignmentAndLength) {
  std::vector<unsigned char> from(256);
  for (std::size_t i = 0; i < from.size(); ++i) from[i] = static_cast<unsigned char>(i * 37 + 1);
  alignas(64) unsigned char to[256];
  for (std::size_t to_offset = 0; to_offset < 64; ++to_offset)
    for (std::size_t from_offset = 0; from_offset < 8; ++from_offset)
      for (std::size_t bytes = 0; bytes <= 150; ++bytes) {
        std::fill(std::begin(to), std::end(to), 0xEE);
        mbk::stream_copy(to + to_offset, from.data() + from_offset, bytes);
        mbk::stream_fence();
        for (std::size_t i = 0; i < sizeof to; ++i) {
          const bool inside = i >= to_offset && i < to_offset + bytes;
          ASSERT_EQ(inside ? from[from_offset + i - to_offset] : 0xEE, to[i])
              << "byte " << i << " of a copy of " << bytes << " bytes to offset " << to_offset
              << " from offset " << from_offset;
        }
      }
}

// stream_transpose8: b[l n + e] = a[8 e + l] for every n up to past a few 8 x 8 blocks (the
// fields of the batch's eight lanes: 9, 111 and 333 numbers for the human model) and every
// alignment of b in its 64-byte line, nothing outside b touched.
TEST(StreamCopy, TransposeOfEightColumnsAtEveryAlignmentAndLength) {
  std::vector<std::size_t> lengths;
  for (std::size_t n = 1; n <= 40; ++n) lengths.push_back(n);
  lengths.insert(lengths.end(), {111, 333});
  for (const std::size_t n : lengths) {
    std::vector<double> a(8 * n);
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.5 + static_cast<double>(i);
    for (std::size_t offset = 0; offset < 8; ++offset) {
      std::vector<double> storage(8 * n + 32, -7.0);
      double* start = storage.data();  // the first 64-byte boundary in storage
      while (reinterpret_cast<std::uintptr_t>(start) % 64 != 0) ++start;
      double* b = start + offset;
      mbk::HeldLine held;
      mbk::stream_transpose8(a.data(), n, b, held);
      mbk::write_held(held);
      mbk::stream_fence();
      for (double* x = storage.data(); x < storage.data() + storage.size(); ++x) {
        const std::ptrdiff_t i = x - b;
        const bool inside = i >= 0 && i < static_cast<std::ptrdiff_t>(8 * n);
        const double expected = inside ? a[i % n * 8 + i / n] : -7.0;
        ASSERT_EQ(expected, *x) << "number " << i << " of b (n " << n << ", b at " << offset
                                << " numbers past a 64-byte boundary)";
      }
    }
  }
}

// Blocks one after the other, as the batch's groups of eight samples write a field: the line two
// blocks share is held by the first and completed by the next; one held when the next block does
// not follow on is written alone (as is the last, by write_held). Every number of every block,
// nothing between or around them.
TEST(StreamCopy, TransposesOfBlocksThatFollowOnAndThatDoNot) {
  for (const std::size_t n : {8, 9, 13, 111})
    for (std::size_t offset = 0; offset < 8; ++offset) {
      const std::size_t blocks = 4, gap = 3;  // blocks 0..2 follow on, block 3 after a gap
      std::vector<double> a(blocks * 8 * n);
      for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.25 + static_cast<double>(i);
      std::vector<double> storage(blocks * 8 * n + gap + 32, -7.0);
      double* start = storage.data();
      while (reinterpret_cast<std::uintptr_t>(start) % 64 != 0) ++start;
      std::vector<double*> b;
      for (std::size_t k = 0; k < blocks; ++k)
        b.push_back(start + offset + k * 8 * n + (k == blocks - 1 ? gap : 0));
      mbk::HeldLine held;
      for (std::size_t k = 0; k < blocks; ++k)
        mbk::stream_transpose8(a.data() + k * 8 * n, n, b[k], held);
      mbk::write_held(held);
      mbk::stream_fence();
      for (double* x = storage.data(); x < storage.data() + storage.size(); ++x) {
        double expected = -7.0;
        for (std::size_t k = 0; k < blocks; ++k) {
          const std::ptrdiff_t i = x - b[k];
          if (i >= 0 && i < static_cast<std::ptrdiff_t>(8 * n))
            expected = a[k * 8 * n + i % n * 8 + i / n];
        }
        ASSERT_EQ(expected, *x) << "number " << x - start << " (n " << n << ", blocks from "
                                << offset << " numbers past a 64-byte boundary)";
      }
    }
}

// b off a double's boundary (numpy's arrays may be: np.frombuffer at an odd offset), after a
// block on one whose last line is held: the same numbers, one at a time, nothing around b
// touched, the held line written first.
TEST(StreamCopy, TransposeToAnyByte) {
  const std::size_t n = 13;
  std::vector<double> a(8 * n);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.75 + static_cast<double>(i);
  for (std::size_t shift = 1; shift < sizeof(double); ++shift) {
    alignas(64) unsigned char storage[2 * 8 * 13 * sizeof(double) + 128];
    std::fill(std::begin(storage), std::end(storage), 0xEE);
    double* first = reinterpret_cast<double*>(storage + 8);  // 8 bytes past a 64-byte boundary
    unsigned char* second = storage + 8 + 8 * n * sizeof(double) + shift;
    mbk::HeldLine held;
    mbk::stream_transpose8(a.data(), n, first, held);
    mbk::stream_transpose8(a.data(), n, reinterpret_cast<double*>(second), held);
    mbk::write_held(held);
    mbk::stream_fence();
    for (std::size_t i = 0; i < sizeof storage; ++i) {
      const std::size_t begin = 8, end = 8 + 8 * n * sizeof(double);
      double x;
      std::size_t at = 0;
      bool inside = true;
      if (i >= begin && i < end) {
        at = (i - begin) / sizeof(double);
        std::memcpy(&x, storage + begin + at * sizeof(double), sizeof x);
      } else if (i >= end + shift && i < end + shift + 8 * n * sizeof(double)) {
        at = (i - end - shift) / sizeof(double);
        std::memcpy(&x, second + at * sizeof(double), sizeof x);
      } else {
        inside = false;
      }
      if (inside)
        ASSERT_EQ(a[at % n * 8 + at / n], x)
            << "number " << at << ", second block " << shift << " bytes off a double's boundary";
      else
        ASSERT_EQ(0xEE, storage[i]) << "byte " << i << " outside both blocks, shift " << shift;
    }
  }
}

}  // namespace
