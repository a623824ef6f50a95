#include "mb_kinematics/io/block_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>

namespace mbk {

namespace {
constexpr std::size_t kAlignment = 4096;  // of memory, offsets and sizes for direct I/O
}  // namespace

BlockFile::BlockFile(const std::string& path, std::uint64_t direct_after)
    : path_(path), direct_after_(direct_after) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) throw std::invalid_argument(path + ": cannot write (" + std::strerror(errno) + ")");
  struct stat st;
  regular_ = ::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode);
  buffer_ = static_cast<char*>(std::aligned_alloc(kAlignment, kBlockBytes));
  if (!buffer_) {
    ::close(fd_);
    throw std::bad_alloc();
  }
}

BlockFile::~BlockFile() {
  if (fd_ >= 0) ::close(fd_);
  std::free(buffer_);
}

void BlockFile::write(const char* data, std::size_t size) {
  while (size > 0) {
    const std::size_t n = std::min(size, kBlockBytes - used_);
    std::memcpy(buffer_ + used_, data, n);
    used_ += n, data += n, size -= n;
    if (used_ == kBlockBytes) write_block();
  }
}

void BlockFile::write_block() {
  if (!tried_direct_ && regular_ && written_ >= direct_after_) try_direct();
  write_all(buffer_, used_);
  used_ = 0;
}

// Every write so far was of whole blocks: the offset is aligned.
void BlockFile::try_direct() {
  tried_direct_ = true;
  const int flags = ::fcntl(fd_, F_GETFL);
  direct_ = flags >= 0 && ::fcntl(fd_, F_SETFL, flags | O_DIRECT) == 0;
}

void BlockFile::page_cache() {
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_DIRECT);
  direct_ = false;
}

void BlockFile::write_all(const char* data, std::size_t size) {
  while (size > 0 && error_ == 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EINVAL && direct_) {  // direct I/O refused after all
      page_cache();
      continue;
    }
    if (n <= 0) {
      error_ = n < 0 ? errno : EIO;
      break;
    }
    data += n, size -= static_cast<std::size_t>(n), written_ += static_cast<std::uint64_t>(n);
    used_direct_ = used_direct_ || direct_;
  }
}

void BlockFile::close() {
  if (fd_ < 0) return;
  if (used_ > 0 && direct_) page_cache();  // the tail is not a whole block
  write_all(buffer_, used_);
  used_ = 0;
  if (::close(fd_) != 0 && error_ == 0) error_ = errno;
  fd_ = -1;
  if (error_ != 0)
    throw std::runtime_error(path_ + ": write failed (" + std::strerror(error_) + ")");
}

}  // namespace mbk
