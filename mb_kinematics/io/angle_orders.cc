#include "mb_kinematics/io/angle_orders.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/name_list.h"

namespace mbk {
namespace {

bool ends_with(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

// The body named `name` or whose joint is, 0 if none.
int body_named(const Model& model, const std::string& name) {
  for (int k = 1; k <= model.body_count(); ++k)
    if (model.bodies[k].name == name || model.bodies[k].joint.name == name) return k;
  return 0;
}

}  // namespace

std::vector<EulerOrder> parse_angle_orders(const Model& model, const std::string& yaml,
                                           const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(printable(path + ": not YAML: " + e.msg));
  }
  if (!root.IsMap())
    throw std::invalid_argument(printable(path + ": expected a map of body or joint name: order"));
  std::vector<int> given(model.bodies.size(), 0);  // the line that names body k
  std::vector<EulerOrder> orders(model.bodies.size(), EulerOrder::kXYZ);
  bool has_default = false;
  EulerOrder fallback = EulerOrder::kXYZ;
  for (const auto& entry : root) {
    const std::string where = path + ":" + std::to_string(entry.first.Mark().line + 1);
    if (!entry.first.IsScalar() || !entry.second.IsScalar())
      throw std::invalid_argument(printable(where + ": expected body or joint name: order"));
    const std::string name = entry.first.as<std::string>();
    EulerOrder order;
    try {
      order = euler_order_from_string(entry.second.as<std::string>());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(printable(where + ": " + name + ": " + e.what()));
    }
    if (name == "default") {
      has_default = true, fallback = order;
      continue;
    }
    const int k = body_named(model, name);
    if (k == 0) throw std::invalid_argument(printable(where + ": no body or joint named " + name));
    if (given[k])
      throw std::invalid_argument(printable(where + ": body " + model.bodies[k].name +
                                            " given an order twice (also on line " +
                                            std::to_string(given[k]) + ")"));
    given[k] = entry.first.Mark().line + 1;
    orders[k] = order;
  }
  std::vector<std::string> missing;
  for (int k = 1; k <= model.body_count(); ++k)
    if (!given[k]) {
      if (!has_default) missing.push_back(model.bodies[k].name);
      orders[k] = fallback;
    }
  if (!missing.empty())
    throw std::invalid_argument(printable(path + ": no order for " + name_list(missing) +
                                          " (name them, or give default: ORDER)"));
  return orders;
}

std::vector<EulerOrder> angle_orders(const Model& model, const std::string& text) {
  if (!ends_with(text, ".yaml") && !ends_with(text, ".yml"))
    return std::vector<EulerOrder>(model.bodies.size(), euler_order_from_string(text));
  std::ifstream in(text);
  if (!in) throw std::invalid_argument(printable(text + ": cannot read the angle orders"));
  std::stringstream s;
  s << in.rdbuf();
  return parse_angle_orders(model, s.str(), text);
}

}  // namespace mbk
