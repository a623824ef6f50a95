// An output of mbk bag written under a temporary name beside it and renamed over PATH only once
// it is whole (commit), so that a failed run never leaves a partial file that looks whole. A
// path the user named that exists and is not a regular file (/dev/stdout, a pipe, a device such
// as /dev/full, or a link to one) is written in place, never replaced.
//
// The temporary file is `PATH.mbk-tmp-PID-XXXXXX`: created by mkstemp (O_CREAT|O_EXCL, so
// never through a link planted at its name; XXXXXX unpredictable), and checked to be still the
// file created (same device and inode, a regular file, not a link) before it is renamed. A link
// at PATH itself is replaced by the rename, never followed. The name carries the owning process:
// a file left by a run that was killed (SIGKILL, a power cut) is removed by the next run on the
// same output once that process is gone; SIGINT, SIGTERM and SIGHUP remove it at once
// (temporary_files.h).
//
// While the temporary file is written, a thread of its own starts the writing of its pages to the
// disk every few milliseconds (Writeback, output_file.cc): ext4 writes a file's delayed blocks
// when a file truncated at its opening (libhdf5's and the writers' O_TRUNC) is closed, and when
// it is renamed over another, on the closing or renaming thread; started beside the computing,
// they are mostly written by then.
#pragma once

#include <sys/types.h>

#include <memory>
#include <string>

namespace mbk_offline {

class OutputFile {
 public:
  // `named`: the user named `path` (--out, --csv); a side file (OUT.errors.csv) is not written
  // in place through whatever is found at its name.
  explicit OutputFile(const std::string& path, bool named = true);
  ~OutputFile();  // removes the temporary file unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& writing() const { return writing_; }  // the path to write to now
  // The written file renamed over the path; throws std::runtime_error if that fails or if the
  // temporary file is no longer the one created.
  void commit();

 private:
  void create_temporary();
  void stop_writeback();
  class Writeback;
  std::unique_ptr<Writeback> writeback_;  // of the temporary file, until commit
  std::string path_, writing_;
  int fd_ = -1;       // the temporary file, open while it is written
  dev_t device_ = 0;  // and its identity
  ino_t inode_ = 0;
  int slot_ = -1;  // its record for removal on signals
  bool committed_ = false;
};

}  // namespace mbk_offline
