// RetainedBlocks (offline/retained_blocks.h): a released block goes to the next request of its
// size, a smaller request takes the front of the smallest kept range that holds it, released
// ranges that touch are joined, the bytes kept never exceed the most held at once, release()
// hands them back.
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
  void* again = blocks.take(4 * kPage);
  EXPECT_EQ(again, first);
  EXPECT_EQ(blocks.kept_bytes(), 0u);
  void* larger = blocks.take(5 * kPage);  // nothing kept holds it: a new block
  EXPECT_NE(larger, first);
  blocks.give(larger, 5 * kPage);
  blocks.give(again, 4 * kPage);
  EXPECT_EQ(blocks.kept_bytes(), 9 * kPage);
}

// A call's arrays, then a chunk's (a tenth of each): the chunk's come out of the call's blocks,
// and once released they join them again, so the next call's fit in them too.
TEST(RetainedBlocks, ChunksTakePartsOfLargerBlocksAndGiveThemBack) {
  RetainedBlocks blocks;
  char* call = static_cast<char*>(blocks.take(30 * kPage));
  std::memset(call, 7, 30 * kPage);
  blocks.give(call, 30 * kPage);
  char* chunk[3];
  for (char*& c : chunk) c = static_cast<char*>(blocks.take(3 * kPage));
  EXPECT_EQ(chunk[0], call);  // front to back, best fit: the rest of the same range
  EXPECT_EQ(chunk[1], call + 3 * kPage);
  EXPECT_EQ(chunk[2], call + 6 * kPage);
  EXPECT_EQ(blocks.kept_bytes(), 21 * kPage);
  EXPECT_EQ(chunk[2][3 * kPage - 1], 7);  // pages touched before
  blocks.give(chunk[1], 3 * kPage);       // not next to the rest yet: a range of its own
  EXPECT_EQ(blocks.kept_ranges(), 2u);
  blocks.give(chunk[0], 3 * kPage);
  blocks.give(chunk[2], 3 * kPage);  // joins both sides
  EXPECT_EQ(blocks.kept_ranges(), 1u);
  EXPECT_EQ(blocks.kept_bytes(), 30 * kPage);
  EXPECT_EQ(blocks.take(30 * kPage), call);
  blocks.give(call, 30 * kPage);
}

TEST(RetainedBlocks, TakesTheSmallestKeptRangeThatHoldsTheRequest) {
  RetainedBlocks blocks;
  char* whole = static_cast<char*>(blocks.take(13 * kPage));
  blocks.give(whole, 13 * kPage);
  char* small = static_cast<char*>(blocks.take(4 * kPage));
  char* between = static_cast<char*>(blocks.take(kPage));  // keeps the other two apart
  char* large = static_cast<char*>(blocks.take(8 * kPage));
  EXPECT_EQ(between, whole + 4 * kPage);
  blocks.give(large, 8 * kPage);
  blocks.give(small, 4 * kPage);
  EXPECT_EQ(blocks.kept_ranges(), 2u);
  EXPECT_EQ(blocks.take(3 * kPage), small);  // 4 pages hold 3: the 8 are left whole
  EXPECT_EQ(blocks.take(5 * kPage), large);
  EXPECT_EQ(blocks.kept_bytes(), 4 * kPage);
  blocks.give(small, 3 * kPage);
  blocks.give(between, kPage);
  blocks.give(large, 5 * kPage);
  EXPECT_EQ(blocks.kept_ranges(), 1u);  // the 13 pages again
  EXPECT_EQ(blocks.kept_bytes(), 13 * kPage);
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
