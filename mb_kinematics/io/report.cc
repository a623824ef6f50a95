#include "mb_kinematics/io/report.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {
namespace {

std::string number(double x) { return format_double(x); }

template <typename Matrix>
std::string json_array(const Matrix& m) {  // row-major
  std::string out = "[";
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) out += (r + c ? ", " : "") + number(m(r, c));
  return out + "]";
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string format_lower_body_table(const std::vector<int>& lower,
                                    const std::vector<std::string>& names) {
  const auto table = lower_body_table(lower);
  std::ostringstream out;
  out << "Lower body arrays, N = " << lower.size() << " (method.md 1)\n";
  for (size_t t = 0; t < table.size(); ++t) {
    char label[16];
    std::snprintf(label, sizeof label, "L^%zu(k)", t);
    out << label << std::string(8 - std::string(label).size(), ' ');
    for (size_t i = 0; i < lower.size(); ++i) {
      const bool shown = t == 0 || table[t - 1][i] != 0;
      char cell[16];
      std::snprintf(cell, sizeof cell, "%4d", table[t][i]);
      out << (shown ? cell : "    ");
    }
    out << "\n";
  }
  if (!names.empty()) {
    out << "bodies:";
    for (size_t i = 0; i < names.size(); ++i) out << " " << i + 1 << "=" << names[i];
    out << "\n";
  }
  return out.str();
}

std::string format_lower_body_csv(const std::vector<int>& lower) {
  std::ostringstream out;
  for (const auto& row : lower_body_table(lower)) {
    for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
    out << "\n";
  }
  return out.str();
}

namespace {  // issue 10: the system quantities and the partial velocities

std::string json_vector(const Vec3<double>& v, bool known) {
  return known ? json_array(v.transpose()) : "null";
}

std::string system_json(const Model& model, const SystemKinematics<double>& s) {
  if (!(s.mass_center.allFinite() && s.velocity.allFinite() && s.acceleration.allFinite() &&
        s.angular_momentum.allFinite()))
    throw std::runtime_error("system quantities not finite (check the state and the masses)");
  const bool g = s.mass > 0;  // no mass center without mass
  std::string out =
      "{\"mass\": " + number(s.mass) + ", \"mass_center\": " + json_vector(s.mass_center, g) +
      ", \"velocity\": " + json_vector(s.velocity, g) +
      ", \"acceleration\": " + json_vector(s.acceleration, g) +
      ", \"linear_momentum\": " + json_vector(s.linear_momentum, g) +
      ", \"angular_momentum\": " + json_vector(s.angular_momentum, g && s.angular_momentum_known);
  if (!s.angular_momentum_known) {
    out += ", \"missing_inertia\": [";
    const std::vector<std::string> names = bodies_without_inertia(model);
    for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + json_string(names[i]);
    out += "]";
  }
  return out + "}";
}

// ", "partial_omega": {speed: [3], ...}, ..." for body k.
std::string partials_json(const Model& model, const PartialVelocities<double>& pv, int k) {
  const std::vector<SpeedColumn> columns = independent_columns(model, pv, k);
  const char* names[] = {"partial_omega", "partial_velocity", "partial_omega_dot",
                         "partial_velocity_dot"};
  const Vec3<double> SpeedColumn::*fields[] = {&SpeedColumn::omega, &SpeedColumn::velocity,
                                               &SpeedColumn::omega_dot, &SpeedColumn::velocity_dot};
  std::string out;
  for (int f = 0; f < 4; ++f) {
    out += std::string(", \"") + names[f] + "\": {";
    for (size_t i = 0; i < columns.size(); ++i) {
      const Vec3<double>& v = columns[i].*fields[f];
      if (!v.allFinite())
        throw std::runtime_error("body " + std::to_string(k) + " '" + model.bodies[k].name +
                                 "': partial velocities not finite");
      out += (i ? ", " : "") + json_string(model.speed_names[columns[i].speed]) + ": " +
             json_array(v.transpose());
    }
    out += "}";
  }
  return out;
}

}  // namespace

std::string format_eval_json(const Model& model, const Data<double>& data,
                             const SystemKinematics<double>* system,
                             const PartialVelocities<double>* pv) {
  std::ostringstream out;
  out << "{\"frame\": " << json_string(model.frame) << ", \"bodies\": [";
  for (int k = 1; k <= model.body_count(); ++k) {
    const bool finite = data.rotation[k].allFinite() && data.origin[k].allFinite() &&
                        data.mass_center[k].allFinite() && data.omega[k].allFinite() &&
                        data.alpha[k].allFinite() && data.mass_center_velocity[k].allFinite() &&
                        data.mass_center_acceleration[k].allFinite();
    if (!finite)
      throw std::runtime_error("body " + std::to_string(k) + " '" + model.bodies[k].name +
                               "': kinematics not finite (check the state, e.g. Euler "
                               "parameters of zero norm)");
    out << (k > 1 ? ",\n  " : "\n  ") << "{\"index\": " << k
        << ", \"name\": " << json_string(model.bodies[k].name)
        << ", \"lower\": " << model.bodies[k].lower
        << ", \"origin\": " << json_array(data.origin[k].transpose())
        << ", \"rotation\": " << json_array(data.rotation[k])
        << ", \"mass_center\": " << json_array(data.mass_center[k].transpose())
        << ", \"omega\": " << json_array(data.omega[k].transpose())
        << ", \"alpha\": " << json_array(data.alpha[k].transpose())
        << ", \"velocity\": " << json_array(data.mass_center_velocity[k].transpose())
        << ", \"acceleration\": " << json_array(data.mass_center_acceleration[k].transpose())
        << (pv ? partials_json(model, *pv, k) : "") << "}";
  }
  out << "\n]";
  if (system) out << ", \"system\": " << system_json(model, *system);
  out << "}\n";
  return out.str();
}

}  // namespace mbk
