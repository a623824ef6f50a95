#include "mb_kinematics/io/report.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

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
    char label[32];
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

std::string format_eval_json(const Model& model, const Data<double>& data) {
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
        << "}";
  }
  out << "\n]}\n";
  return out.str();
}

}  // namespace mbk
