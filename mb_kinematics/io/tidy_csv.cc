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

TidyCsvWriter::TidyCsvWriter(const std::string& path, const Model& model, bool errors)
    : model_(model),
      path_(path),
      file_(std::fopen(path.c_str(), "w")),
      body_cells_(model.bodies.size()) {
  if (!file_) throw std::invalid_argument(path + ": cannot write (" + std::strerror(errno) + ")");
  for (int k = 0; k <= model.body_count(); ++k) total_mass_ += model.bodies[k].mass;
  for (int k = 1; k <= model.body_count(); ++k)
    body_cells_[k] = "," + model.bodies[k].name + "," + std::to_string(k) + "," +
                     std::to_string(model.bodies[k].lower);
  std::fputs(header(), file_);
  if (errors) std::fputs(errors_header(), file_);
  std::fputc('\n', file_);
  errors_ = errors;
  buffer_.reserve(kBufferBytes + (1 << 14));
}

TidyCsvWriter::~TidyCsvWriter() {
  if (file_) std::fclose(file_);
}

const char* TidyCsvWriter::header() {
  return "stamp,body,index,lower_body,origin_x,origin_y,origin_z,qx,qy,qz,qw,mass_center_x,"
         "mass_center_y,mass_center_z,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z,"
         "velocity_x,velocity_y,velocity_z,acceleration_x,acceleration_y,acceleration_z";
}

const char* TidyCsvWriter::errors_header() {
  return ",alpha_se_x,alpha_se_y,alpha_se_z,acceleration_se_x,acceleration_se_y,acceleration_se_z";
}

void TidyCsvWriter::flush() {
  std::fwrite(buffer_.data(), 1, buffer_.size(), file_);  // an error is seen by close()
  buffer_.clear();
}

namespace {

// The cells after a row's body cells, formatted into one buffer and appended at once.
class Cells {
 public:
  void number(double x) {  // ",x"
    *end_++ = ',';
    end_ = write_shortest(end_, x);
  }
  void empty(int n) {  // n empty cells
    std::memset(end_, ',', n);
    end_ += n;
  }
  void end_row(std::string& text) {
    *end_++ = '\n';
    text.append(cells_, end_);
    end_ = cells_;
  }

 private:
  static constexpr int kMaxCells = 28;  // 22 values and 6 error bars
  char cells_[kMaxCells * (1 + kMaxDoubleChars) + 1];
  char* end_ = cells_;
};

}  // namespace

void TidyCsvWriter::format(double stamp, const Data<double>& d, std::string& text,
                           const std::vector<Vec3<double>>* alpha_se,
                           const std::vector<Vec3<double>>* acceleration_se) const {
  const bool have = errors_ && alpha_se && acceleration_se;
  char stamp_text[400];  // %.9f of the largest double fits
  const int stamp_size = std::snprintf(stamp_text, sizeof stamp_text, "%.9f", stamp);
  Cells cells;
  for (int k = 1; k <= model_.body_count(); ++k) {
    text.append(stamp_text, stamp_size).append(body_cells_[k]);
    const Eigen::Quaterniond q(d.rotation[k]);
    for (int i = 0; i < 3; ++i) cells.number(d.origin[k][i]);
    for (double x : {q.x(), q.y(), q.z(), q.w()}) cells.number(x);
    for (const auto* v :
         {&d.mass_center, &d.omega, &d.alpha, &d.mass_center_velocity, &d.mass_center_acceleration})
      for (int i = 0; i < 3; ++i) cells.number((*v)[k][i]);
    if (have)
      for (const auto* v : {alpha_se, acceleration_se})
        for (int i = 0; i < 3; ++i) cells.number((*v)[k][i]);
    else if (errors_)
      cells.empty(6);
    cells.end_row(text);
  }
  if (total_mass_ <= 0) return;
  SystemKinematics<double> system;  // every link with mass, the root link included
  system_kinematics(model_, d, system, Level::kAcceleration);
  const Vec3<double>&p = system.mass_center, &v = system.velocity, &a = system.acceleration;
  text.append(stamp_text, stamp_size).append(",system,0,0");
  cells.empty(7);  // no origin, orientation
  for (int i = 0; i < 3; ++i) cells.number(p[i]);
  cells.empty(6);  // no omega, alpha
  for (const Vec3<double>* x : {&v, &a})
    for (int i = 0; i < 3; ++i) cells.number((*x)[i]);
  if (errors_) cells.empty(6);
  cells.end_row(text);
}

void TidyCsvWriter::write(double stamp, const Data<double>& d,
                          const std::vector<Vec3<double>>* alpha_se,
                          const std::vector<Vec3<double>>* acceleration_se) {
  format(stamp, d, buffer_, alpha_se, acceleration_se);
  if (buffer_.size() >= kBufferBytes) flush();
}

void TidyCsvWriter::write_text(const std::string& text) {
  if (!buffer_.empty()) flush();
  std::fwrite(text.data(), 1, text.size(), file_);
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
