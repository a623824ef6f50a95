#include "mb_kinematics/io/tidy_csv.h"

#include <Eigen/Geometry>
#include <cstring>

#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {

TidyCsvWriter::TidyCsvWriter(const std::string& path, const Model& model, bool errors,
                             const std::string& system)
    : model_(model),
      file_(path),
      errors_(errors),
      body_cells_(model.bodies.size()),
      system_cells_("," + system + ",0,0") {
  for (int k = 0; k <= model.body_count(); ++k) total_mass_ += model.bodies[k].mass;
  for (int k = 1; k <= model.body_count(); ++k)
    body_cells_[k] = "," + model.bodies[k].name + "," + std::to_string(k) + "," +
                     std::to_string(model.bodies[k].lower);
  file_.write(std::string(header()) + (errors ? errors_header() : "") + "\n");
}

const char* TidyCsvWriter::header() {
  return "stamp,body,index,lower_body,origin_x,origin_y,origin_z,qx,qy,qz,qw,mass_center_x,"
         "mass_center_y,mass_center_z,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z,"
         "velocity_x,velocity_y,velocity_z,acceleration_x,acceleration_y,acceleration_z";
}

const char* TidyCsvWriter::errors_header() {
  return ",alpha_se_x,alpha_se_y,alpha_se_z,acceleration_se_x,acceleration_se_y,acceleration_se_z";
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
  char stamp_text[kMaxStampChars];  // %.9f of the largest double fits
  const int stamp_size = static_cast<int>(write_stamp(stamp_text, origin_, stamp) - stamp_text);
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
  text.append(stamp_text, stamp_size).append(system_cells_);
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
  buffer_.clear();
  format(stamp, d, buffer_, alpha_se, acceleration_se);
  file_.write(buffer_);
}

void TidyCsvWriter::write_text(const std::string& text) { file_.write(text); }

}  // namespace mbk
