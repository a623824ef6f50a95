#include "mb_kinematics/offline/output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace mbk_offline {
namespace {

bool in_place(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

}  // namespace

OutputFile::OutputFile(const std::string& path)
    : path_(path),
      writing_(in_place(path) ? path : path + ".mbk-tmp-" + std::to_string(getpid())) {}

OutputFile::~OutputFile() {
  if (!committed_ && writing_ != path_) std::remove(writing_.c_str());
}

void OutputFile::commit() {
  if (writing_ != path_ && std::rename(writing_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(path_ + ": cannot rename " + writing_ + " to it (" +
                             std::strerror(errno) + ")");
  committed_ = true;
}

}  // namespace mbk_offline
