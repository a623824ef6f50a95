// RetainedBlocks (offline/retained_blocks.h): a released block goes to the next request of its
// size, the blocks kept never exceed the most held at once, release() hands them back.
#include "mb_kinematics/offline/retained_blocks.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>

namespace mbk {
namespace {

const std::size_t kPage = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));

TEST(RetainedBlocks, ReleasedBlockGoesToTheNextRequestOfItsSize) {
  RetainedBlocks blocks;
  void* first = blocks.take(4 * kPage - 8);  // rounded up to 4 pages
  std::memset(first, 7, 4 * kPage);
  blocks.give(first, 4 * kPage - 8);
  EXPECT_EQ(blocks.kept_bytes(), 4 * kPage);
  void* other = blocks.take(2 * kPage);  // another size: a new block
  EXPECT_NE(other, first);
  void* again = blocks.take(4 * kPage);
  EXPECT_EQ(again, first);
  EXPECT_EQ(blocks.kept_bytes(), 0u);
  blocks.give(other, 2 * kPage);
  blocks.give(again, 4 * kPage);
  EXPECT_EQ(blocks.kept_bytes(), 6 * kPage);
}

TEST(RetainedBlocks, KeepsNoMoreThanTheMostHeldAtOnce) {
  RetainedBlocks blocks;
  blocks.give(blocks.take(4 * kPage), 4 * kPage);  // held at most 4 pages: kept
  EXPECT_EQ(blocks.kept_bytes(), 4 * kPage);
  void* large = blocks.take(8 * kPage);  // held at most 8 pages now
  blocks.give(large, 8 * kPage);         // 4 + 8 kept would exceed 8: unmapped
  EXPECT_EQ(blocks.kept_bytes(), 4 * kPage);
}

TEST(RetainedBlocks, ReleaseHandsEveryKeptBlockBack) {
  RetainedBlocks blocks;
  void* a = blocks.take(kPage);
  void* b = blocks.take(3 * kPage);
  blocks.give(a, kPage);
  blocks.give(b, 3 * kPage);
  EXPECT_EQ(blocks.release(), 4 * kPage);
  EXPECT_EQ(blocks.kept_bytes(), 0u);
  void* c = blocks.take(kPage);  // a new mapping, writeable
  std::memset(c, 1, kPage);
  blocks.give(c, kPage);
}

}  // namespace
}  // namespace mbk
