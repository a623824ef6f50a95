// release_freed_heap (mb_kinematics/ros/heap_trim.h): memory freed between live blocks, as a
// robot_description's XML leaves it, goes back to the system, so the node's RSS falls after
// its model is read.
#include "mb_kinematics/ros/heap_trim.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <memory>
#include <vector>

namespace {

// Resident set size of this process, in bytes (/proc/self/statm, second field).
long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

// Of the memory freed between live blocks, most goes back: the RSS falls by more than half of
// what the blocks added to it (measured here, so that neither the page size nor the
// allocator's overhead per block sets the figure), while one block in 1000 stays live.
TEST(HeapTrim, ReturnsMemoryFreedBetweenLiveBlocks) {
  constexpr int kBlocks = 400000, kBytes = 200;  // 80 MB in small blocks, as a parser makes
  const long base = resident_bytes();
  std::vector<std::unique_ptr<char[]>> blocks(kBlocks);
  for (auto& b : blocks) {
    b = std::make_unique<char[]>(kBytes);
    b[0] = 1;  // touched: resident
  }
  for (int i = 0; i < kBlocks; ++i)
    if (i % 1000 != 999) blocks[i].reset();  // freed, with a live block every 200 kB
  const long before = resident_bytes();
  ASSERT_GT(before - base, long{kBlocks} * kBytes / 2) << "the blocks were never resident";
  mbk_ros::release_freed_heap();
  const long after = resident_bytes();
  EXPECT_GT(before - after, (before - base) / 2)
      << "RSS " << (base >> 20) << " MB, with the blocks " << (before >> 20) << " MB, trimmed "
      << (after >> 20) << " MB";
}

}  // namespace
