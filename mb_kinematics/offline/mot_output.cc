#include "mb_kinematics/offline/mot_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>

#include "mb_kinematics/core/euler_angles.h"
#include "mb_kinematics/core/segment_frames.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk_offline {
namespace {

constexpr int kRowsWidth = 20;  // nRows' digits, padded with spaces (OpenSim trims them)
constexpr std::size_t kFlushBytes = 1 << 20;
constexpr off_t kRowsAt = sizeof "Coordinates\nversion=1\nnRows=" - 1;  // nRows' digits
constexpr double kDegrees = 180.0 / M_PI;

}  // namespace

std::string MotOutput::label(const std::string& coordinate) {
  std::string out = coordinate;
  for (char& c : out)
    if (c == ' ' || c == '\t') c = '_';
  return out;
}

std::array<std::string, 3> MotOutput::angle_labels(const std::string& body, mbk::EulerOrder order) {
  const std::array<int, 3> axes = mbk::euler_axes(order);
  const bool numbered = !mbk::is_tait_bryan(order);
  std::array<std::string, 3> out;
  for (int i = 0; i < 3; ++i) {
    out[i] = label(body) + "_" + static_cast<char>('X' + axes[i]);
    if (numbered) out[i] += static_cast<char>('1' + i);
  }
  return out;
}

// The lines before the rows: the header and the labels; throws if two labels are one.
std::string MotOutput::header(const mbk::Model& model, const mbk::Model& bodies) const {
  std::vector<std::string> labels{"time"};
  if (!columns_.angles.empty())
    for (int k = 1; k <= bodies.body_count(); ++k)
      for (const std::string& l : angle_labels(bodies.bodies[k].name, columns_.angles[k]))
        labels.push_back(l);
  if (columns_.coordinates)
    for (const std::string& name : model.coordinate_names) labels.push_back(label(name));
  std::set<std::string> seen;
  for (const std::string& l : labels)
    if (!seen.insert(l).second)
      throw std::invalid_argument(shown_ + ": two columns would be labelled '" + l +
                                  "' (OpenSim reads columns by label)");
  std::string out = "Coordinates\nversion=1\nnRows=" + std::string(kRowsWidth, ' ') +
                    "\nnColumns=" + std::to_string(labels.size()) + "\ninDegrees=yes\nendheader\n";
  for (std::size_t i = 0; i < labels.size(); ++i) out += (i ? "\t" : "") + labels[i];
  return out + "\n";
}

MotOutput::MotOutput(const std::string& path, const std::string& shown, const mbk::Model& model,
                     const mbk::Model& bodies, const MotColumns& columns)
    : shown_(shown),
      bodies_(bodies),
      columns_(columns),
      angles_(columns.angles),
      scale_(columns.coordinates ? model.nq : 0, 1.0) {
  if (!columns.angles.empty() && columns.angles.size() != bodies.bodies.size())
    throw std::invalid_argument(shown + ": " + std::to_string(columns.angles.size()) +
                                " angle orders for " + std::to_string(bodies.bodies.size()) +
                                " bodies and R");
  buffer_ = header(model, bodies);
  if (columns.coordinates)
    for (const mbk::Body& b : model.bodies)
      for (int i = 0; i < mbk::coordinate_count(b.joint.type); ++i)
        if (mbk::coordinate_kind(b.joint.type, i) == mbk::CoordinateKind::kAngle)
          scale_[b.q_index + i] = kDegrees;
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) throw std::invalid_argument(shown + ": cannot write (" + std::strerror(errno) + ")");
  if (::lseek(fd_, 0, SEEK_CUR) < 0) {
    ::close(fd_);
    throw std::invalid_argument(shown +
                                ": --mot needs a file it can seek in (its header counts the "
                                "rows), not a pipe or terminal");
  }
}

MotOutput::~MotOutput() {
  if (fd_ >= 0) ::close(fd_);
}

void MotOutput::write(const mbk::OfflineRow& row, const mbk::Data<double>& data,
                      const mbk::EulerAngleTrack* angles) {
  char stamp[mbk::kMaxStampChars];  // as the CSV writes it
  buffer_.append(stamp, mbk::write_stamp(stamp, origin_, row.stamp));
  char cells[mbk::kMaxDoubleChars + 1];
  cells[0] = '\t';
  if (!columns_.angles.empty())
    for (int k = 1; k <= bodies_.body_count(); ++k) {
      const mbk::Vec3<double>& x =
          angles ? angles->last(k)
                 : angles_.next(k, mbk::relative_motion(bodies_, data, k).rotation);  // SJK's
      for (int i = 0; i < 3; ++i)
        buffer_.append(cells, mbk::write_shortest(cells + 1, x[i] * kDegrees));
    }
  for (std::size_t c = 0; c < scale_.size(); ++c)
    buffer_.append(cells, mbk::write_shortest(cells + 1, row.state.position[c] * scale_[c]));
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
      ::pwrite(fd_, count.data(), count.size(), kRowsAt) != static_cast<ssize_t>(count.size()))
    error_ = errno ? errno : EIO;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0 && error_ == 0) error_ = errno;
  if (error_ != 0) fail(error_);
}

}  // namespace mbk_offline
