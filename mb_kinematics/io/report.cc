#include "mb_kinematics/io/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/segment_frames.h"
#include "mb_kinematics/core/utf8.h"
#include "mb_kinematics/io/number_format.h"

namespace mbk {
namespace {

// A JSON number: inf and NaN have none, so that no JSON written is invalid.
std::string number(double x) {
  if (!std::isfinite(x)) throw std::runtime_error("a value is not finite: no JSON written");
  return format_double(x);
}

template <typename Matrix>
std::string json_array(const Matrix& m) {  // row-major
  std::string out = "[";
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) out += (r + c ? ", " : "") + number(m(r, c));
  return out + "]";
}

// Widths of the text table: the label column and each entry, with at least one space between.
int digits(size_t n) { return static_cast<int>(std::to_string(n).size()); }

}  // namespace

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const size_t n = utf8_length(text, i);
    if (c == '"' || c == '\\') {
      out += std::string("\\") + text[i];
    } else if (c < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", c);
      out += escape;
    } else if (n == 0) {
      out += "\\ufffd";
    } else {
      out += text.substr(i, n);
    }
    i += n == 0 ? 1 : n;
  }
  return out + "\"";
}

void write_lower_body_table(std::ostream& out, const std::vector<int>& lower,
                            const std::vector<std::string>& names) {
  const int rows = lower_body_table_rows(lower);
  const int label_width = std::max(8, digits(rows - 1) + 6);  // "L^" t "(k)" and a space
  const int cell_width = std::max(4, digits(lower.size()) + 1);
  out << "Lower body arrays, N = " << lower.size() << " (method.md 1)\n";
  std::vector<int> previous;
  std::string line;
  for_each_lower_body_row(lower, [&](int t, const std::vector<int>& row) {
    const std::string label = "L^" + std::to_string(t) + "(k)";
    line = label + std::string(label_width - label.size(), ' ');
    for (size_t i = 0; i < row.size(); ++i) {
      const bool shown = t == 0 || previous[i] != 0;
      const std::string cell = shown ? std::to_string(row[i]) : "";
      line.append(cell_width - cell.size(), ' ').append(cell);
    }
    out << line << "\n";
    previous = row;
  });
  if (!names.empty()) {
    out << "bodies:";
    for (size_t i = 0; i < names.size(); ++i) out << " " << i + 1 << "=" << printable(names[i]);
    out << "\n";
  }
}

std::string format_lower_body_table(const std::vector<int>& lower,
                                    const std::vector<std::string>& names) {
  std::ostringstream out;
  write_lower_body_table(out, lower, names);
  return out.str();
}

void write_lower_body_csv(std::ostream& out, const std::vector<int>& lower) {
  std::string line;
  for_each_lower_body_row(lower, [&](int, const std::vector<int>& row) {
    line.clear();
    for (size_t i = 0; i < row.size(); ++i)
      line.append(i ? "," : "").append(std::to_string(row[i]));
    out << line << "\n";
  });
}

std::string format_lower_body_csv(const std::vector<int>& lower) {
  std::ostringstream out;
  write_lower_body_csv(out, lower);
  return out.str();
}

namespace {  // doc/method.md 9: the system quantities and the partial velocities

std::string json_vector(const Vec3<double>& v, bool known) {
  return known ? json_array(v.transpose()) : "null";
}

std::string system_json(const Model& model, const SystemKinematics<double>& s,
                        const std::vector<std::string>& incomplete) {
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
  if (!incomplete.empty()) {
    out += ", \"incomplete\": [";
    for (size_t i = 0; i < incomplete.size(); ++i)
      out += (i ? ", " : "") + json_string(incomplete[i]);
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
        throw std::runtime_error("body " + std::to_string(k) + " '" +
                                 printable(model.bodies[k].name) +
                                 "': partial velocities not finite");
      out += (i ? ", " : "") + json_string(model.speed_names[columns[i].speed]) + ": " +
             json_array(v.transpose());
    }
    out += "}";
  }
  return out;
}

// ", "omega_body": [3], ..." and/or ", "relative_rotation": [[3]x3], ..." for body k.
std::string segment_frames_json(const Model& model, const Data<double>& data, int k,
                                const EvalExtras& extra) {
  std::string out;
  if (extra.body_axes) {
    const std::pair<const char*, const Vec3<double>*> fields[] = {
        {"omega_body", &data.omega[k]},
        {"alpha_body", &data.alpha[k]},
        {"velocity_body", &data.mass_center_velocity[k]},
        {"acceleration_body", &data.mass_center_acceleration[k]}};
    for (const auto& [name, x] : fields)
      out +=
          std::string(", \"") + name + "\": " + json_array(in_body_axes(data, k, *x).transpose());
  }
  if (extra.relative) {
    const RelativeMotion<double> m = relative_motion(model, data, k);
    out += ", \"relative_rotation\": " + json_array(m.rotation) +
           ", \"relative_omega\": " + json_array(m.omega.transpose()) +
           ", \"relative_alpha\": " + json_array(m.alpha.transpose());
  }
  return out;
}

}  // namespace

std::string format_eval_json(const Model& model, const Data<double>& data,
                             const SystemKinematics<double>* system,
                             const PartialVelocities<double>* pv,
                             const std::vector<std::string>& incomplete, const EvalExtras& extra) {
  std::ostringstream out;
  out << "{\"frame\": " << json_string(model.frame) << ", \"bodies\": [";
  for (int k = 1; k <= model.body_count(); ++k) {
    const bool finite = data.rotation[k].allFinite() && data.origin[k].allFinite() &&
                        data.mass_center[k].allFinite() && data.omega[k].allFinite() &&
                        data.alpha[k].allFinite() && data.mass_center_velocity[k].allFinite() &&
                        data.mass_center_acceleration[k].allFinite();
    if (!finite)
      throw std::runtime_error("body " + std::to_string(k) + " '" +
                               printable(model.bodies[k].name) +
                               "': kinematics not finite (check the state, e.g. Euler "
                               "parameters of zero norm)");
    out << (k > 1 ? ",\n  " : "\n  ") << "{\"index\": " << k
        << ", \"name\": " << json_string(model.bodies[k].name)
        << ", \"lower\": " << model.bodies[k].lower
        << ", \"origin\": " << json_array(data.origin[k].transpose())
        << ", \"rotation\": " << json_array(data.rotation[k])
        << ", \"mass_center\": " << json_array(data.mass_center[k].transpose())
        << ", \"mass\": " << number(model.bodies[k].mass)
        << ", \"local_mass_center\": " << json_array(model.bodies[k].mass_center.transpose())
        << ", \"inertia\": "
        << (model.bodies[k].has_inertia ? json_array(model.bodies[k].inertia) : "null")
        << ", \"omega\": " << json_array(data.omega[k].transpose())
        << ", \"alpha\": " << json_array(data.alpha[k].transpose())
        << ", \"velocity\": " << json_array(data.mass_center_velocity[k].transpose())
        << ", \"acceleration\": " << json_array(data.mass_center_acceleration[k].transpose())
        << (pv ? partials_json(model, *pv, k) : "") << segment_frames_json(model, data, k, extra)
        << "}";
  }
  out << "\n]";
  if (system) out << ", \"system\": " << system_json(model, *system, incomplete);
  out << "}\n";
  return out.str();
}

}  // namespace mbk
