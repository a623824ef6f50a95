#include "mb_kinematics/offline/mot_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "mb_kinematics/io/number_format.h"

namespace mbk_offline {
namespace {

constexpr int kRowsWidth = 20;  // nRows' digits, padded with spaces (OpenSim trims them)
constexpr std::size_t kFlushBytes = 1 << 20;

}  // namespace

std::string MotOutput::label(const std::string& coordinate) {
  std::string out = coordinate;
  for (char& c : out)
    if (c == ' ' || c == '\t') c = '_';
  return out;
}

MotOutput::MotOutput(const std::string& path, const std::string& shown, const mbk::Model& model)
    : shown_(shown), scale_(model.nq, 1.0) {
  for (const mbk::Body& b : model.bodies)
    for (int i = 0; i < mbk::coordinate_count(b.joint.type); ++i)
      if (mbk::coordinate_kind(b.joint.type, i) == mbk::CoordinateKind::kAngle)
        scale_[b.q_index + i] = 180.0 / M_PI;
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) throw std::invalid_argument(shown + ": cannot write (" + std::strerror(errno) + ")");
  if (::lseek(fd_, 0, SEEK_CUR) < 0) {
    ::close(fd_);
    throw std::invalid_argument(shown +
                                ": --mot needs a file it can seek in (its header counts the "
                                "rows), not a pipe or terminal");
  }
  buffer_ = "Coordinates\nversion=1\nnRows=";
  rows_at_ = static_cast<off_t>(buffer_.size());
  buffer_ += std::string(kRowsWidth, ' ') + "\nnColumns=" + std::to_string(model.nq + 1) +
             "\ninDegrees=yes\nendheader\ntime";
  for (const std::string& name : model.coordinate_names) buffer_ += "\t" + label(name);
  buffer_ += "\n";
}

MotOutput::~MotOutput() {
  if (fd_ >= 0) ::close(fd_);
}

void MotOutput::write(const mbk::OfflineRow& row) {
  char stamp[mbk::kMaxStampChars];  // as the CSV writes it
  buffer_.append(stamp, mbk::write_stamp(stamp, origin_, row.stamp));
  char cells[mbk::kMaxDoubleChars + 1];
  for (std::size_t c = 0; c < scale_.size(); ++c) {
    cells[0] = '\t';
    buffer_.append(cells, mbk::write_shortest(cells + 1, row.state.position[c] * scale_[c]));
  }
  buffer_ += '\n';
  ++rows_;
  if (buffer_.size() >= kFlushBytes) flush();
}

void MotOutput::flush() {
  const char* at = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0 && error_ == 0) {
    const ssize_t n = ::write(fd_, at, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) error_ = n < 0 ? errno : EIO;
    if (n > 0) at += n, left -= static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

void MotOutput::fail(int error) const {
  throw std::runtime_error(shown_ + ": write failed (" + std::strerror(error) + ")");
}

void MotOutput::close() {
  if (fd_ < 0) return;
  flush();
  const std::string count = std::to_string(rows_);
  if (error_ == 0 &&
      ::pwrite(fd_, count.data(), count.size(), rows_at_) != static_cast<ssize_t>(count.size()))
    error_ = errno ? errno : EIO;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0 && error_ == 0) error_ = errno;
  if (error_ != 0) fail(error_);
}

}  // namespace mbk_offline
