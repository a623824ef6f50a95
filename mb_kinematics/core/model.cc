#include "mb_kinematics/core/model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "mb_kinematics/core/inertia.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/core/printable.h"

namespace mbk {
namespace {

// The message holds the model's names: escaped (a NUL in one would end what() there).
[[noreturn]] void fail(const Body& body, int k, const std::string& what) {
  throw std::invalid_argument(
      printable("body " + std::to_string(k) + " '" + body.name + "': " + what));
}

bool all_finite(const Eigen::MatrixXd& m) { return m.allFinite(); }

void validate_body(Body& body, int k) {
  if (body.name.empty()) fail(body, k, "has no name");
  Joint& joint = body.joint;
  if (!all_finite(joint.axis)) fail(body, k, "joint axis is not finite");
  if (!all_finite(joint.offset)) fail(body, k, "joint origin (q_k) is not finite");
  if (!all_finite(joint.rotation)) fail(body, k, "joint rotation (C_k) is not finite");
  if (!all_finite(body.mass_center)) fail(body, k, "mass_center is not finite");
  if (!std::isfinite(body.mass) || body.mass < 0) fail(body, k, "mass must be finite and >= 0");
  const std::string inertia = body.has_inertia ? inertia_problem(body.inertia) : "";
  if (!inertia.empty()) fail(body, k, "inertia " + inertia);
  const Mat3<double> c = joint.rotation;
  if ((c.transpose() * c - Mat3<double>::Identity()).norm() > 1e-9 || c.determinant() < 0)
    fail(body, k, "joint rotation (C_k) is not a proper rotation");
  if (joint_traits(joint.type).uses_axis) {
    // Lengths scaled by the largest component first (stable*): the length of [1e200, 1e200, 0]
    // is 1.4e200, not an overflow to inf that would normalize it to [0, 0, 0].
    if (joint.axis.stableNorm() < 1e-12) fail(body, k, "joint axis is zero");
    // Normalize unless already unit to rounding, so that finalizing twice changes nothing.
    if (std::abs(joint.axis.squaredNorm() - 1.0) > 4 * std::numeric_limits<double>::epsilon())
      joint.axis.stableNormalize();
    if (std::abs(joint.axis.norm() - 1.0) > 1e-12) fail(body, k, "joint axis cannot be normalized");
  }
}

// Refuses masses whose sum a double cannot hold (two links of 1.7e308 kg): the system's mass
// and mass center would be inf or NaN, whichever loader read them.
void check_total_mass(const Model& model) {
  double total = 0;
  for (const Body& body : model.bodies) total += body.mass;
  if (!std::isfinite(total))
    throw std::invalid_argument("the bodies' masses sum to more than a double holds: refused");
}

// Refuses a name given to two coordinates (or two speeds), naming both joints: a ball joint
// `s` has `s/alpha`, which a joint named `s/alpha` would have too.
void check_unique(const Model& model, const std::vector<std::string>& names, bool speeds) {
  std::unordered_map<std::string, int> owner;  // name -> body
  owner.reserve(names.size());
  int i = 0;
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const int n =
        speeds ? speed_count(body.joint.type, model.speeds) : coordinate_count(body.joint.type);
    for (int end = i + n; i < end; ++i) {
      const auto [it, inserted] = owner.emplace(names[i], k);
      if (inserted) continue;
      const Body& first = model.bodies[it->second];
      fail(body, k,
           std::string(speeds ? "speed" : "coordinate") + " name '" + names[i] + "' of joint '" +
               body.joint.name + "' is also one of joint '" + first.joint.name + "' (body " +
               std::to_string(it->second) + " '" + first.name + "')");
    }
  }
}

// Orders the mimics so that each comes after the mimic that sets its source (a mimic of a
// mimic reads the updated value); refuses a coordinate mimicking twice and cycles, naming them.
void order_mimics(Model& model) {
  std::unordered_map<int, int> mimic_of;  // coordinate -> its mimic
  for (size_t i = 0; i < model.mimics.size(); ++i)
    if (!mimic_of.emplace(model.mimics[i].coordinate, static_cast<int>(i)).second)
      throw std::invalid_argument("mimic: '" +
                                  printable(model.coordinate_names[model.mimics[i].coordinate]) +
                                  "' mimics two joints");
  std::vector<int> level(model.mimics.size(), -1);  // hops to a source that is no mimic
  std::vector<char> on_path(model.mimics.size(), 0);
  std::vector<int> path;  // unresolved mimics from `start` towards a resolved source
  auto name = [&](int i) { return model.coordinate_names[model.mimics[i].coordinate]; };
  for (size_t start = 0; start < model.mimics.size(); ++start) {
    path.clear();
    int i = static_cast<int>(start);
    while (i >= 0 && level[i] < 0) {
      if (on_path[i]) {
        std::string cycle;
        for (auto j = std::find(path.begin(), path.end(), i); j != path.end(); ++j)
          cycle += name(*j) + " -> ";
        throw std::invalid_argument(printable("mimic joints form a cycle: " + cycle + name(i)));
      }
      on_path[i] = 1;
      path.push_back(i);
      const auto source = mimic_of.find(model.mimics[i].source);
      i = source == mimic_of.end() ? -1 : source->second;
    }
    int next = i < 0 ? -1 : level[i];
    for (auto j = path.rbegin(); j != path.rend(); ++j) level[*j] = ++next;
    for (int j : path) on_path[j] = 0;
  }
  std::vector<int> order(model.mimics.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return level[a] < level[b]; });
  std::vector<Mimic> sorted;
  for (int i : order) sorted.push_back(model.mimics[i]);
  model.mimics = sorted;
}

// bodies[0] stands for R: named after it, with the mass, mass center and inertia of the link
// fixed in R that a URDF's root link gives (its mass counts in the system), nothing else.
void set_root(Model& model) {
  const Body& given = model.bodies[0];
  Body root;
  root.name = model.frame;
  root.mass = given.mass;
  root.mass_center = given.mass_center;
  root.inertia = given.inertia;
  root.has_inertia = given.has_inertia;
  if (!std::isfinite(root.mass) || root.mass < 0) fail(root, 0, "mass must be finite and >= 0");
  if (!all_finite(root.mass_center)) fail(root, 0, "mass_center is not finite");
  model.bodies[0] = root;
}

}  // namespace

std::vector<int> Model::lower_body_array() const {
  std::vector<int> lower;
  for (int k = 1; k <= body_count(); ++k) lower.push_back(bodies[k].lower);
  return lower;
}

int Model::body_index(const std::string& name) const {
  for (int k = 1; k <= body_count(); ++k)
    if (bodies[k].name == name) return k;
  return -1;
}

int Model::coordinate_index(const std::string& name) const {
  for (int i = 0; i < nq; ++i)
    if (coordinate_names[i] == name) return i;
  return -1;
}

int Model::speed_index(const std::string& name) const {
  for (int i = 0; i < nv; ++i)
    if (speed_names[i] == name) return i;
  return -1;
}

void finalize_model(Model& model) {
  if (model.bodies.size() < 2) throw std::invalid_argument("model has no bodies");
  set_root(model);
  validate_lower_body_array(model.lower_body_array());
  std::set<std::string> body_names = {model.frame}, joint_names;
  model.nq = model.nv = 0;
  model.coordinate_names.clear();
  model.speed_names.clear();
  for (int k = 1; k <= model.body_count(); ++k) {
    Body& body = model.bodies[k];
    validate_body(body, k);
    if (!body_names.insert(body.name).second) fail(body, k, "name is used twice (or is R's)");
    if (body.joint.name.empty()) body.joint.name = body.name + "_joint";
    if (!joint_names.insert(body.joint.name).second)
      fail(body, k, "joint name '" + body.joint.name + "' is used twice");
    body.depth = model.bodies[body.lower].depth + 1;
    body.q_index = model.nq;
    body.v_index = model.nv;
    const JointType type = body.joint.type;
    for (const std::string& suffix : coordinate_suffixes(type))
      model.coordinate_names.push_back(body.joint.name + (suffix.empty() ? "" : "/" + suffix));
    for (const std::string& suffix : speed_suffixes(type, model.speeds))
      model.speed_names.push_back(body.joint.name + (suffix.empty() ? "" : "/" + suffix));
    model.nq += coordinate_count(type);
    model.nv += speed_count(type, model.speeds);
  }
  check_unique(model, model.coordinate_names, false);
  check_unique(model, model.speed_names, true);
  for (const Mimic& m : model.mimics) {
    if (m.coordinate < 0 || m.coordinate >= model.nq)
      throw std::invalid_argument("mimic: coordinate " + std::to_string(m.coordinate) +
                                  " is not in the model");
    const std::string mimic = "mimic '" + model.coordinate_names[m.coordinate] + "': ";
    if (m.source < 0 || m.source >= model.nq)
      throw std::invalid_argument(mimic + "its source is not in the model");
    if (m.source == m.coordinate) throw std::invalid_argument(mimic + "it mimics itself");
    if (!std::isfinite(m.multiplier) || !std::isfinite(m.offset))
      throw std::invalid_argument(mimic + "multiplier or offset not finite");
    if (model.nq != model.nv)
      throw std::invalid_argument("mimic joints need coordinate-derivative speeds");
  }
  check_total_mass(model);
  order_mimics(model);
  model.steps = make_body_steps(model);
}

Model make_bare_model(const std::vector<int>& lower, JointType type) {
  validate_lower_body_array(lower);
  Model model;
  model.bodies.resize(lower.size() + 1);
  for (size_t i = 0; i < lower.size(); ++i) {
    Body& body = model.bodies[i + 1];
    body.name = "B" + std::to_string(i + 1);
    body.lower = lower[i];
    body.joint.name = "J" + std::to_string(i + 1);
    body.joint.type = type;
    if (body.lower != 0) body.joint.offset = Vec3<double>(1.0, 0.0, 0.0);
    body.mass_center = Vec3<double>(0.5, 0.0, 0.0);
    body.mass = 1.0;
  }
  finalize_model(model);
  return model;
}

}  // namespace mbk
