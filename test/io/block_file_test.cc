// BlockFile (io/block_file.h): the bytes written are the file's, byte for byte, in writes of any
// size across block bounds, below and past the size from which it writes past the page cache
// (direct I/O where the filesystem takes it: checked here by opening a file with O_DIRECT), and a
// full disk or an unwritable path is an error naming the file.
#include "mb_kinematics/io/block_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Whether the directory's filesystem takes O_DIRECT.
bool direct_io_allowed(const std::string& dir) {
  const std::string probe = dir + "block_file_probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_DIRECT, 0644);
  if (fd >= 0) ::close(fd);
  std::remove(probe.c_str());
  return fd >= 0;
}

// `bytes` pseudo-random bytes written in pieces of 1 to 40,000 bytes.
std::string write_pieces(mbk::BlockFile& file, std::size_t bytes) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> piece(1, 40000), byte(0, 255);
  std::string all;
  all.reserve(bytes);
  while (all.size() < bytes) {
    std::string p(std::min<std::size_t>(piece(rng), bytes - all.size()), '\0');
    for (char& c : p) c = static_cast<char>(byte(rng));
    file.write(p);
    all += p;
  }
  return all;
}

TEST(BlockFileTest, ASmallFileIsItsBytesThroughThePageCache) {
  const std::string path = ::testing::TempDir() + "block_small.bin";
  mbk::BlockFile file(path);
  const std::string bytes = write_pieces(file, 3 * mbk::BlockFile::kBlockBytes + 12345);
  file.close();
  EXPECT_FALSE(file.direct());
  EXPECT_TRUE(read_file(path) == bytes);
}

// 14 MiB and a tail that is not a whole block, direct I/O (where allowed) past the first 8 MiB
// (here; a GiB in mbk bag).
TEST(BlockFileTest, ALargeFileIsItsBytesPastThePageCache) {
  const std::string path = ::testing::TempDir() + "block_large.bin";
  mbk::BlockFile file(path, 8 << 20);
  const std::string bytes = write_pieces(file, (14 << 20) + 777);
  file.close();
  EXPECT_EQ(file.direct(), direct_io_allowed(::testing::TempDir()));
  const std::string back = read_file(path);
  ASSERT_EQ(back.size(), bytes.size());
  EXPECT_TRUE(back == bytes);
  std::remove(path.c_str());
}

TEST(BlockFileTest, AFullDiskIsAnErrorNamingTheFile) {
  mbk::BlockFile file("/dev/full");
  file.write(std::string(1000, 'x'));
  try {
    file.close();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "/dev/full: write failed (No space left on device)");
  }
}

TEST(BlockFileTest, AnUnwritablePathIsAnErrorNamingIt) {
  try {
    mbk::BlockFile file("/nonexistent/dir/x.csv");
    ADD_FAILURE() << "opened";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/x.csv: cannot write (No such file or directory)");
  }
}

}  // namespace
