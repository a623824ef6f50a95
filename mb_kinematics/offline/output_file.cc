#include "mb_kinematics/offline/output_file.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace mbk_offline {
namespace {

const char kTag[] = ".mbk-tmp-";

bool in_place(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

// The permissions a file created by open(..., 0666) would have.
mode_t default_mode() {
  static const mode_t mode = [] {
    const mode_t mask = umask(0);
    umask(mask);
    return 0666 & ~mask;
  }();
  return mode;
}

}  // namespace

OutputFile::OutputFile(const std::string& path, bool named) : path_(path) {
  if (named && in_place(path)) {
    writing_ = path;
    return;
  }
  create_temporary();
}

void OutputFile::create_temporary() {
  std::string name = path_ + kTag + std::to_string(getpid()) + "-XXXXXX";
  fd_ = mkostemp(name.data(), O_CLOEXEC);
  if (fd_ < 0)
    throw std::invalid_argument(path_ + ": cannot create a file beside it (" +
                                std::strerror(errno) + ")");
  writing_ = name;
  struct stat st;
  if (fchmod(fd_, default_mode()) != 0 || fstat(fd_, &st) != 0) {
    const std::string error = std::strerror(errno);
    unlink(writing_.c_str());
    close(fd_);
    throw std::invalid_argument(writing_ + ": cannot set up (" + error + ")");
  }
  device_ = st.st_dev, inode_ = st.st_ino;
}

OutputFile::~OutputFile() {
  if (!committed_ && fd_ >= 0) unlink(writing_.c_str());
  if (fd_ >= 0) close(fd_);
}

void OutputFile::commit() {
  if (fd_ >= 0) {
    struct stat st;
    if (lstat(writing_.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_dev != device_ ||
        st.st_ino != inode_)
      throw std::runtime_error(writing_ +
                               ": replaced while it was written (by another process?): " + path_ +
                               " left as it was");
    if (std::rename(writing_.c_str(), path_.c_str()) != 0)
      throw std::runtime_error(path_ + ": cannot rename " + writing_ + " to it (" +
                               std::strerror(errno) + ")");
  }
  committed_ = true;
}

}  // namespace mbk_offline
