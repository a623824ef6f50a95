// stream_copy (offline/stream_copy.h): the bytes of std::memcpy, at every alignment of either
// end and every length up to past a few 32-byte blocks, and nothing outside them touched.
#include "mb_kinematics/offline/stream_copy.h"

#include <gtest/gtest.h>

#include <cstdint>
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

}  // namespace
