#include "mb_kinematics/io/tidy_csv.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "mb_kinematics/core/euler_angles.h"
#include "mb_kinematics/core/segment_frames.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {

TidyCsvWriter::TidyCsvWriter(const std::string& path, const Model& model, bool errors,
                             const std::string& system, const TidyCsvExtras& extras)
    : model_(model),
      file_(path),
      errors_(errors),
      extras_(extras),
      angles_(extras.angles),
      body_cells_(model.bodies.size()),
      system_cells_("," + system + ",0,0") {
  for (int k = 0; k <= model.body_count(); ++k) total_mass_ += model.bodies[k].mass;
  for (int k = 1; k <= model.body_count(); ++k)
    body_cells_[k] = "," + model.bodies[k].name + "," + std::to_string(k) + "," +
                     std::to_string(model.bodies[k].lower);
  if (!extras.angles.empty() && extras.angles.size() != model.bodies.size())
    throw std::invalid_argument("tidy CSV: " + std::to_string(extras.angles.size()) +
                                " angle orders for " + std::to_string(model.bodies.size()) +
                                " bodies and R");
  file_.write(std::string(header()) + (errors ? errors_header() : "") + extras_header(extras) +
              "\n");
}

const char* TidyCsvWriter::header() {
  return "stamp,body,index,lower_body,origin_x,origin_y,origin_z,qx,qy,qz,qw,mass_center_x,"
         "mass_center_y,mass_center_z,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z,"
         "velocity_x,velocity_y,velocity_z,acceleration_x,acceleration_y,acceleration_z";
}

const char* TidyCsvWriter::errors_header() {
  return ",alpha_se_x,alpha_se_y,alpha_se_z,acceleration_se_x,acceleration_se_y,acceleration_se_z";
}

std::string TidyCsvWriter::extras_header(const TidyCsvExtras& extras) {
  std::string out;
  auto xyz = [&out](const char* name) {
    for (const char* axis : {"_x", "_y", "_z"}) out += std::string(",") + name + axis;
  };
  if (extras.body_axes)
    for (const char* name : {"omega_body", "alpha_body", "velocity_body", "acceleration_body"})
      xyz(name);
  if (!extras.angles.empty()) {
    out += ",angle_order,angle_1,angle_2,angle_3";
    xyz("relative_omega");
    xyz("relative_alpha");
  }
  return out;
}

namespace {

// The cells after a row's body cells, formatted into one buffer and appended at once.
class Cells {
 public:
  void number(double x) {  // ",x"
    *end_++ = ',';
    end_ = write_shortest(end_, x);
  }
  void text(const std::string& x) {  // ",x"
    *end_++ = ',';
    end_ = std::copy(x.begin(), x.end(), end_);
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
  // 22 values, 6 error bars, 12 in body axes, an order (3 letters) and 9 of the joint's motion.
  static constexpr int kMaxCells = 50;
  char cells_[kMaxCells * (1 + kMaxDoubleChars) + 1];
  char* end_ = cells_;
};

// The extras' cells of body k (TidyCsvExtras); with angles, the track's next for body k.
void extra_cells(const Model& model, const TidyCsvExtras& extras, const Data<double>& d, int k,
                 EulerAngleTrack& angles, Cells& cells) {
  if (extras.body_axes)
    for (const auto* v :
         {&d.omega, &d.alpha, &d.mass_center_velocity, &d.mass_center_acceleration}) {
      const Vec3<double> x = in_body_axes(d, k, (*v)[k]);
      for (int i = 0; i < 3; ++i) cells.number(x[i]);
    }
  if (extras.angles.empty()) return;
  const RelativeMotion<double> m = relative_motion(model, d, k);
  const Vec3<double>& x = angles.next(k, m.rotation);
  cells.text(to_string(angles.order(k)));
  for (const Vec3<double>* v : {&x, &m.omega, &m.alpha})
    for (int i = 0; i < 3; ++i) cells.number((*v)[i]);
}

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
    extra_cells(model_, extras_, d, k, angles_, cells);
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
  cells.empty((extras_.body_axes ? 12 : 0) + (extras_.angles.empty() ? 0 : 10));
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
