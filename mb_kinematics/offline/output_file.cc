#include "mb_kinematics/offline/output_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <mutex>
#include <random>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/offline/temporary_files.h"

namespace mbk_offline {
namespace {

const char kTag[] = ".mbk-tmp-";

bool in_place(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

// The folder of `path` ("." for a bare name) and its last component.
std::pair<std::string, std::string> split(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return {".", path};
  return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

// The process that owns a temporary file named `name` (`BASE.mbk-tmp-PID` or
// `BASE.mbk-tmp-PID-XXXXXX`) of output `base`, or 0 when `name` is not one.
pid_t owner(const std::string& name, const std::string& base) {
  const std::string prefix = base + kTag;
  if (name.compare(0, prefix.size(), prefix) != 0) return 0;
  const char* digits = name.c_str() + prefix.size();
  char* end = nullptr;
  const long pid = std::strtol(digits, &end, 10);
  if (end == digits || !(*end == '\0' || *end == '-') || pid <= 0) return 0;
  return static_cast<pid_t>(pid);
}

// Six random letters and digits, as mkostemp's XXXXXX: a name no one can plant a file at ahead.
std::string random_suffix() {
  static const char kChars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  static std::mutex lock;  // outputs may be opened on several threads
  static std::mt19937_64 random{std::random_device{}()};
  const std::lock_guard<std::mutex> hold(lock);
  std::string suffix(6, 'X');
  for (char& c : suffix) c = kChars[random() % (sizeof kChars - 1)];
  return suffix;
}

bool running(pid_t pid) { return pid == getpid() || kill(pid, 0) == 0 || errno == EPERM; }

// Removes the temporary files of `path` left by runs that were killed (their process is gone):
// this user's regular files only, each named in a note.
void remove_leftovers(const std::string& path) {
  const auto [folder, base] = split(path);
  DIR* dir = opendir(folder.c_str());
  if (!dir) return;
  while (const dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    const pid_t pid = owner(name, base);
    if (pid == 0 || running(pid)) continue;
    const std::string leftover = folder + "/" + name;
    struct stat st;
    if (lstat(leftover.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != geteuid())
      continue;
    if (unlink(leftover.c_str()) == 0)
      std::cerr << "mbk: note: removed " << mbk::printable(leftover)
                << ", left by an interrupted run (process " << pid << " has ended)\n";
  }
  closedir(dir);
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

// Every kPeriod until stopped, the writing of the file's dirty pages started
// (sync_file_range(SYNC_FILE_RANGE_WRITE) starts it, and waits for none of it; its errors are
// the writer's to meet): see output_file.h.
class OutputFile::Writeback {
 public:
  explicit Writeback(int fd) : fd_(fd), thread_([this] { run(); }) {}
  ~Writeback() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    stopped_.notify_all();
    thread_.join();
  }

 private:
  static constexpr std::chrono::milliseconds kPeriod{10};
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stopped_.wait_for(lock, kPeriod, [this] { return stop_; })) {
#ifdef __linux__
      sync_file_range(fd_, 0, 0, SYNC_FILE_RANGE_WRITE);
#endif
    }
  }
  int fd_;
  std::mutex mutex_;
  std::condition_variable stopped_;
  bool stop_ = false;
  std::thread thread_;  // last: started once the fields above are made
};

OutputFile::OutputFile(const std::string& path, bool named) : path_(path) {
  if (named && in_place(path)) {
    writing_ = path;
    return;
  }
  remove_leftovers(path);
  create_temporary();
}

void OutputFile::create_temporary() {
  // The name goes to the signal handler (record_temporary) before the file exists: made first
  // (mkostemp), a signal before its recording left it behind (test_h5_signal_leaves_nothing on a
  // busy machine). A signal in between removes no file (the name is this process's own).
  const std::string stem = path_ + kTag + std::to_string(getpid()) + "-";
  for (int attempt = 1; fd_ < 0; ++attempt) {
    const std::string name = stem + random_suffix();
    slot_ = record_temporary(name);
    fd_ = open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd_ >= 0) {
      writing_ = name;
      break;
    }
    const int error = errno;
    forget_temporary(slot_);
    if (error != EEXIST || attempt == 100)
      throw std::invalid_argument(path_ + ": cannot create a file beside it (" +
                                  std::strerror(error) + ")");
  }
  struct stat st;
  if (fchmod(fd_, default_mode()) != 0 || fstat(fd_, &st) != 0) {
    const std::string error = std::strerror(errno);
    unlink(writing_.c_str());
    forget_temporary(slot_);
    close(fd_);
    throw std::invalid_argument(writing_ + ": cannot set up (" + error + ")");
  }
  device_ = st.st_dev, inode_ = st.st_ino;
  try {
    writeback_ = std::make_unique<Writeback>(fd_);
  } catch (const std::system_error&) {  // no thread: the pages are written at the close
  }
}

void OutputFile::stop_writeback() { writeback_.reset(); }

OutputFile::~OutputFile() {
  stop_writeback();
  if (!committed_ && fd_ >= 0) unlink(writing_.c_str());
  forget_temporary(slot_);
  if (fd_ >= 0) close(fd_);
}

void OutputFile::commit() {
  stop_writeback();
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
