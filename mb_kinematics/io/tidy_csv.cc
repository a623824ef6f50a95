#include "mb_kinematics/io/tidy_csv.h"

#include <Eigen/Geometry>
#include <charconv>
#include <cstring>
#include <stdexcept>

#include "mb_kinematics/core/system_kinematics.h"

namespace mbk {

TidyCsvWriter::TidyCsvWriter(const std::string& path, const Model& model)
    : model_(model), path_(path), file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw std::invalid_argument(path + ": cannot write (" + std::strerror(errno) + ")");
  for (int k = 0; k <= model.body_count(); ++k) total_mass_ += model.bodies[k].mass;
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

// The shortest text that reads back as the same double.
void TidyCsvWriter::number(double x) {
  char buf[32];
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  const auto end = std::to_chars(buf, buf + sizeof buf, x + 0.0).ptr;
  *end = '\0';
#else
  std::snprintf(buf, sizeof buf, "%.17g", x + 0.0);
#endif
  std::fputc(',', file_);
  std::fputs(buf, file_);
}

void TidyCsvWriter::write(double stamp, const Data<double>& d) {
  char stamp_text[32];
  std::snprintf(stamp_text, sizeof stamp_text, "%.9f", stamp);
  for (int k = 1; k <= model_.body_count(); ++k) {
    std::fprintf(file_, "%s,%s,%d,%d", stamp_text, model_.bodies[k].name.c_str(), k,
                 model_.bodies[k].lower);
    const Eigen::Quaterniond q(d.rotation[k]);
    for (int i = 0; i < 3; ++i) number(d.origin[k][i]);
    for (double x : {q.x(), q.y(), q.z(), q.w()}) number(x);
    for (const auto* v :
         {&d.mass_center, &d.omega, &d.alpha, &d.mass_center_velocity, &d.mass_center_acceleration})
      for (int i = 0; i < 3; ++i) number((*v)[k][i]);
    std::fputc('\n', file_);
  }
  if (total_mass_ <= 0) return;
  SystemKinematics<double> system;  // every link with mass, the root link included
  system_kinematics(model_, d, system, Level::kAcceleration);
  const Vec3<double>&p = system.mass_center, &v = system.velocity, &a = system.acceleration;
  std::fprintf(file_, "%s,system,0,0%s", stamp_text, ",,,,,,,");  // no origin, orientation
  for (int i = 0; i < 3; ++i) number(p[i]);
  std::fputs(",,,,,,", file_);  // no omega, alpha
  for (const Vec3<double>* x : {&v, &a})
    for (int i = 0; i < 3; ++i) number((*x)[i]);
  std::fputc('\n', file_);
}

void TidyCsvWriter::close() {
  if (!file_) return;
  const bool ok = std::ferror(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok || !closed) throw std::runtime_error(path_ + ": write failed (disk full?)");
}

}  // namespace mbk
