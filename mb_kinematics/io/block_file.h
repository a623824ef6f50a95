// Bytes appended to a file a block at a time (1 MiB). A regular file past its first GiB is
// written with direct I/O (O_DIRECT: from this buffer to the disk, not copied into the page
// cache) where its filesystem allows it: beyond what the page cache absorbs, its copy was most of
// the time of writing mbk bag's large CSVs (on the project's machine 16.5 GB took 34.6 s through
// the page cache, 11.6 s direct; doc/speed.md). Smaller files, devices (/dev/null, /dev/full),
// pipes and filesystems without direct I/O (tmpfs) are written through the page cache. The bytes
// are the same either way. ROS-free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace mbk {

class BlockFile {
 public:
  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;
  static constexpr std::uint64_t kDirectAfter = std::uint64_t{1} << 30;

  // Creates or truncates `path`; throws std::invalid_argument naming it if it cannot be opened.
  // direct_after: the bytes written through the page cache before direct I/O is tried.
  explicit BlockFile(const std::string& path, std::uint64_t direct_after = kDirectAfter);
  ~BlockFile();
  BlockFile(const BlockFile&) = delete;
  BlockFile& operator=(const BlockFile&) = delete;

  void write(const char* data, std::size_t size);  // an error is kept for close()
  void write(const std::string& text) { write(text.data(), text.size()); }
  // Writes what is left and closes; throws std::runtime_error naming the file and the error if
  // any write failed (a full disk). Destroyed without close(), what is buffered is not written.
  void close();
  bool direct() const { return used_direct_; }  // some blocks went past the page cache

 private:
  void write_block();  // the buffer's whole block
  void write_all(const char* data, std::size_t size);
  void try_direct();  // from here on, where the file and filesystem allow it
  void page_cache();  // from here on, through the page cache

  std::string path_;
  int fd_ = -1;
  char* buffer_ = nullptr;  // kBlockBytes, aligned for direct I/O
  std::size_t used_ = 0;
  std::uint64_t direct_after_, written_ = 0;
  bool regular_ = false, direct_ = false, tried_direct_ = false, used_direct_ = false;
  int error_ = 0;  // the first write's errno
};

}  // namespace mbk
