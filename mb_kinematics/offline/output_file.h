// An output of mbk bag written under a temporary name beside it (`PATH.mbk-tmp-PID`) and renamed
// over PATH only once it is whole (commit), so that a failed run never leaves a partial file
// that looks whole. A path that exists and is not a regular file (/dev/stdout, a pipe, a device
// such as /dev/full) is written in place, never replaced.
#pragma once

#include <string>

namespace mbk_offline {

class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  ~OutputFile();  // removes the temporary file unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& writing() const { return writing_; }  // the path to write to now
  // The written file renamed over the path; throws std::runtime_error if that fails.
  void commit();

 private:
  std::string path_, writing_;
  bool committed_ = false;
};

}  // namespace mbk_offline
