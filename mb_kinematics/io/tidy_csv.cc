#include "mb_kinematics/io/tidy_csv.h"

#include <Eigen/Geometry>
#include <cstring>
#include <stdexcept>

#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {

namespace {
constexpr size_t kBufferBytes = 1 << 16;  // written out when full
}  // namespace

TidyCsvWriter::TidyCsvWriter(const std::string& path, const Model& model)
    : model_(model),
      path_(path),
      file_(std::fopen(path.c_str(), "w")),
      body_cells_(model.bodies.size()),
      buffer_(kBufferBytes) {
  if (!file_) throw std::invalid_argument(path + ": cannot write (" + std::strerror(errno) + ")");
  for (int k = 0; k <= model.body_count(); ++k) total_mass_ += model.bodies[k].mass;
  for (int k = 1; k <= model.body_count(); ++k)
    body_cells_[k] = "," + model.bodies[k].name + "," + std::to_string(k) + "," +
                     std::to_string(model.bodies[k].lower);
  std::fputs(header(), file_);
  std::fputc('\n', file_);
}

TidyCsvWriter::~TidyCsvWriter() {
  if (file_) std::fclose(file_);
}

const char* TidyCsvWriter::header() {
  return "stamp,body,index,lower_body,origin_x,origin_y,origin_z,qx,qy,qz,qw,mass_center_x,"
         "mass_center_y,mass_center_z,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z,"
         "velocity_x,velocity_y,velocity_z,acceleration_x,acceleration_y,acceleration_z";
}

void TidyCsvWriter::flush() {
  std::fwrite(buffer_.data(), 1, used_, file_);  // an error is seen by close()
  used_ = 0;
}

void TidyCsvWriter::number(double x) {
  if (used_ + 1 + kMaxDoubleChars > buffer_.size()) flush();
  buffer_[used_++] = ',';
  used_ = write_shortest(buffer_.data() + used_, x) - buffer_.data();
}

void TidyCsvWriter::text(const char* s, size_t n) {
  if (used_ + n > buffer_.size()) flush();
  if (n > buffer_.size()) {  // a body name longer than the buffer
    std::fwrite(s, 1, n, file_);
    return;
  }
  std::memcpy(buffer_.data() + used_, s, n);
  used_ += n;
}

void TidyCsvWriter::write(double stamp, const Data<double>& d) {
  char stamp_text[400];  // once per sample; %.9f of the largest double fits
  const size_t stamp_size = std::snprintf(stamp_text, sizeof stamp_text, "%.9f", stamp);
  for (int k = 1; k <= model_.body_count(); ++k) {
    text(stamp_text, stamp_size);
    text(body_cells_[k]);
    const Eigen::Quaterniond q(d.rotation[k]);
    for (int i = 0; i < 3; ++i) number(d.origin[k][i]);
    for (double x : {q.x(), q.y(), q.z(), q.w()}) number(x);
    for (const auto* v :
         {&d.mass_center, &d.omega, &d.alpha, &d.mass_center_velocity, &d.mass_center_acceleration})
      for (int i = 0; i < 3; ++i) number((*v)[k][i]);
    end_row();
  }
  if (total_mass_ <= 0) return;
  SystemKinematics<double> system;  // every link with mass, the root link included
  system_kinematics(model_, d, system, Level::kAcceleration);
  const Vec3<double>&p = system.mass_center, &v = system.velocity, &a = system.acceleration;
  static const char kSystem[] = ",system,0,0,,,,,,,";  // no origin, orientation
  text(stamp_text, stamp_size);
  text(kSystem, sizeof kSystem - 1);
  for (int i = 0; i < 3; ++i) number(p[i]);
  text(",,,,,,", 6);  // no omega, alpha
  for (const Vec3<double>* x : {&v, &a})
    for (int i = 0; i < 3; ++i) number((*x)[i]);
  end_row();
}

void TidyCsvWriter::close() {
  if (!file_) return;
  flush();
  const bool ok = std::ferror(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok || !closed) throw std::runtime_error(path_ + ": write failed (disk full?)");
}

}  // namespace mbk
