#include "mb_kinematics/io/yaml_scene.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "mb_kinematics/core/inertia.h"
#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/rpy.h"
#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/io/yaml_bare_scene.h"

namespace mbk {
namespace {

// `what` holds the scene's names: escaped here, as a NUL in one would end what() there.
struct SceneError : std::invalid_argument {
  SceneError(const YAML::Node& node, const std::string& what)
      : std::invalid_argument(std::to_string(node.Mark().line + 1) + ": " + printable(what)) {}
};

double read_number(const YAML::Node& node, const std::string& field) {
  if (!node.IsScalar()) throw SceneError(node, field + " must be a number");
  double value = 0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw SceneError(node, field + " must be a number, not '" + node.Scalar() + "'");
  }
  if (!std::isfinite(value)) throw SceneError(node, field + " is not finite");
  return value;
}

Vec3<double> read_vec3(const YAML::Node& node, const std::string& field) {
  if (!node.IsSequence() || node.size() != 3)
    throw SceneError(node, field + " must be a list of 3 numbers");
  return Vec3<double>(read_number(node[0], field), read_number(node[1], field),
                      read_number(node[2], field));
}

// `body_node` gives the line when the field is missing (a missing key's node has no line).
// `earlier` maps the names of R (0) and of bodies 1..k-1 to their numbers.
int read_lower(const YAML::Node& body_node, const std::unordered_map<std::string, int>& earlier,
               int k) {
  const std::string field = "body " + std::to_string(k) + " lower";
  const YAML::Node node = body_node["lower"];
  if (!node) throw SceneError(body_node, field + " is missing");
  const auto by_name = earlier.find(node.Scalar());  // an earlier body's name, or R's
  if (by_name != earlier.end()) return by_name->second;
  int lower = -1;
  try {
    lower = node.as<int>();
  } catch (const YAML::Exception&) {
    throw SceneError(node, field + " '" + node.Scalar() +
                               "' is neither an earlier body's name nor a number below " +
                               std::to_string(k));
  }
  if (lower < 0 || lower >= k)
    throw SceneError(node, field + " = " + std::to_string(lower) + ", must be 0 <= L(k) < k");
  return lower;
}

// euler_order: XYZ (default), ZXY, ZXZ, ... or 312, ... for ball_123 and free_123 joints.
void read_euler_order(const YAML::Node& node, Joint& joint, const std::string& where) {
  if (!takes_euler_order(joint.type))
    throw SceneError(node, where + ": euler_order is for ball_123 and free_123 joints, not " +
                               to_string(joint.type));
  try {
    joint.euler_order = euler_order_from_string(node.Scalar());
  } catch (const std::invalid_argument& e) {
    throw SceneError(node, where + ": " + e.what());
  }
}

void read_joint(const YAML::Node& body_node, Body& body, int k) {
  const std::string where = "body " + std::to_string(k) + " joint";
  const YAML::Node node = body_node["joint"];
  if (!node || !node.IsMap())
    throw SceneError(node ? node : body_node, where + " must be a map with a type");
  if (node["name"]) body.joint.name = node["name"].Scalar();
  if (!node["type"]) throw SceneError(node, where + " has no type");
  try {
    body.joint.type = joint_type_from_string(node["type"].Scalar());
  } catch (const std::invalid_argument& e) {
    throw SceneError(node["type"], where + ": " + e.what());
  }
  if (node["euler_order"]) read_euler_order(node["euler_order"], body.joint, where);
  if (node["origin"]) body.joint.offset = read_vec3(node["origin"], where + " origin");
  if (node["rpy"]) {
    const Vec3<double> rpy = read_vec3(node["rpy"], where + " rpy");
    body.joint.rotation = rotation_from_rpy(rpy.x(), rpy.y(), rpy.z());
  }
  if (node["axis"]) {
    body.joint.axis = read_vec3(node["axis"], where + " axis");
    if (body.joint.axis.norm() == 0) throw SceneError(node["axis"], where + " axis is zero");
  }
}

// inertia: [ixx, iyy, izz, ixy, ixz, iyz], about G_k in Bk's axes (as URDF's <inertia>).
void read_inertia(const YAML::Node& node, Body& body, int k) {
  const std::string field = "body " + std::to_string(k) + " '" + body.name + "' inertia";
  if (!node.IsSequence() || node.size() != 6)
    throw SceneError(node, field + " must be a list of 6 numbers [ixx, iyy, izz, ixy, ixz, iyz]");
  double c[6];
  for (int i = 0; i < 6; ++i) c[i] = read_number(node[i], field);
  body.inertia = inertia_matrix(c[0], c[1], c[2], c[3], c[4], c[5]);
  body.has_inertia = true;
  const std::string problem = inertia_problem(body.inertia);
  if (!problem.empty()) throw SceneError(node, field + " " + problem);
}

Model read_scene(const YAML::Node& root) {
  if (!root.IsMap())
    throw SceneError(root, "a scene is a map with 'bodies' (see doc/conventions.md)");
  Model model;
  if (root["frame"]) {
    model.frame = root["frame"].Scalar();
    if (model.frame.empty()) throw SceneError(root["frame"], "frame must be a name");
  }
  if (root["speeds"]) {
    const std::string speeds = root["speeds"].Scalar();
    if (speeds == "angular_velocity")
      model.speeds = SpeedKind::kAngularVelocity;
    else if (speeds != "coordinate_derivatives")
      throw SceneError(
          root["speeds"],
          "speeds must be coordinate_derivatives or angular_velocity, not '" + speeds + "'");
  }
  if (root["lower_body_array"] && !root["bodies"]) {  // a bare scene
    const YAML::Node array = root["lower_body_array"];
    if (!array.IsSequence()) throw SceneError(array, "lower_body_array must be a list");
    std::vector<int> lower;
    for (const YAML::Node& entry : array) {
      const double value = read_number(entry, "lower_body_array");
      if (value != std::floor(value) || std::abs(value) > 1e9)
        throw SceneError(entry,
                         "lower_body_array entry '" + entry.Scalar() + "' is not an integer");
      lower.push_back(static_cast<int>(value));
    }
    const std::string type = root["joint_type"] ? root["joint_type"].Scalar() : "ball_123";
    try {
      return make_bare_model(lower, joint_type_from_string(type));
    } catch (const std::invalid_argument& e) {
      throw SceneError(root["lower_body_array"], e.what());
    }
  }
  const YAML::Node bodies = root["bodies"];
  if (!bodies || !bodies.IsSequence() || bodies.size() == 0)
    throw SceneError(root, "scene has no 'bodies' list");
  model.bodies.resize(1);
  std::unordered_map<std::string, int> earlier = {{model.frame, 0}};
  for (size_t i = 0; i < bodies.size(); ++i) {
    const YAML::Node node = bodies[i];
    const int k = static_cast<int>(i) + 1;
    if (!node.IsMap()) throw SceneError(node, "body " + std::to_string(k) + " must be a map");
    Body body;
    if (!node["name"]) throw SceneError(node, "body " + std::to_string(k) + " has no name");
    body.name = node["name"].Scalar();
    body.lower = read_lower(node, earlier, k);
    earlier.emplace(body.name, k);  // a duplicate name keeps the first; finalize_model refuses it
    read_joint(node, body, k);
    if (node["mass_center"])
      body.mass_center = read_vec3(node["mass_center"], body.name + " mass_center");
    if (node["mass"]) body.mass = read_number(node["mass"], body.name + " mass");
    if (node["inertia"]) read_inertia(node["inertia"], body, k);
    model.bodies.push_back(body);
  }
  try {
    finalize_model(model);
  } catch (const std::invalid_argument& e) {
    throw SceneError(bodies, e.what());
  }
  return model;
}

Model parse_scene(const std::string& text, const std::string& source) {
  try {
    Model bare;
    if (read_bare_scene(text, bare)) return bare;  // without the node tree
    return read_scene(YAML::Load(text));
  } catch (const YAML::DeepRecursion& e) {  // its own message is "bad file"
    throw std::invalid_argument(source + ":" + std::to_string(e.mark.line + 1) +
                                ": malformed YAML: nested " + std::to_string(e.depth()) +
                                " levels deep, too deep to read");
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(source + ":" + std::to_string(e.mark.line + 1) +
                                ": malformed YAML: " + e.msg);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ":" + e.what());
  }
}

}  // namespace

// Messages hold names and yaml-cpp's text: control characters escaped to keep them one line.
Model load_yaml_scene_string(const std::string& text, const std::string& source) {
  try {
    return parse_scene(text, source);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(printable(e.what()));
  }
}

Model load_yaml_scene_file(const std::string& path) {
  return load_yaml_scene_string(read_text_file(path, "scene file"), path);
}

}  // namespace mbk
