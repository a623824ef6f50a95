#include "mb_kinematics/io/load_model.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"
#include "mb_kinematics/io/mjcf_model.h"
#include "mb_kinematics/io/sdf_model.h"
#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/yaml_scene.h"

namespace mbk {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// An `.xml` file by its first element: MJCF (<mujoco>), SDFormat (<sdf>) or URDF (<robot>).
Model load_xml_file(const std::string& path) {
  const std::string xml = read_text_file(path, "URDF, MJCF or SDFormat file");
  if (is_mjcf_text(xml)) return load_mjcf_file(path);
  if (is_sdf_text(xml)) return load_sdf_file(path);
  return load_urdf_file(path);
}

// The model of a file that is not BVH: a URDF, an MJCF or SDFormat file or a YAML scene.
Model load_robot_file(const std::string& path) {
  if (ends_with(path, ".urdf")) return load_urdf_file(path);
  if (ends_with(path, ".xml")) return load_xml_file(path);
  if (ends_with(path, ".sdf")) return load_sdf_file(path);
  if (ends_with(path, ".yaml") || ends_with(path, ".yml")) return load_yaml_scene_file(path);
  if (ends_with(path, ".xacro"))
    throw std::invalid_argument(path + ": a xacro file: expand it first (xacro " + path +
                                " > robot.urdf, from ROS's xacro package) and give the .urdf, or "
                                "load robot_description yourself and give no model");
  throw std::invalid_argument(
      path + ": unknown model file type (expected .urdf, .xml, .sdf, .yaml, .bvh)");
}

}  // namespace

bool is_bvh_file(const std::string& path) {
  std::string tail = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return tail == ".bvh";
}

ModelFile read_model_file(const std::string& path, const BvhModelOptions& bvh) {
  ModelFile file;
  if (!is_bvh_file(path)) {
    file.model = load_robot_file(path);
    return file;
  }
  file.bvh = read_bvh(path);
  file.model = model_from_bvh(*file.bvh, bvh);
  file.missing_segments = bvh_missing_segments(*file.bvh, bvh);
  return file;
}

Model load_model_file(const std::string& path, const BvhModelOptions& bvh) {
  return read_model_file(path, bvh).model;
}

Model load_xml_string(const std::string& xml, const std::string& source) {
  if (is_mjcf_text(xml)) return load_mjcf_string(xml, source);
  if (is_sdf_text(xml)) return load_sdf_string(xml, source);
  return load_urdf_string(xml, source);
}

bool is_model_text(const std::string& path_or_text) {
  const std::size_t first = path_or_text.find_first_not_of(" \t\r\n");
  return (first != std::string::npos && path_or_text[first] == '<') ||
         path_or_text.find('\n') != std::string::npos;
}

Model load_model(const std::string& path_or_text, const BvhModelOptions* bvh,
                 const std::string& source) {
  const bool text = is_model_text(path_or_text);
  if (bvh && (text || !is_bvh_file(path_or_text)))
    throw std::invalid_argument("scale, body mass and sex apply to a .bvh model file only");
  if (!text) return load_model_file(path_or_text, bvh ? *bvh : BvhModelOptions());
  const std::size_t first = path_or_text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
    throw std::invalid_argument(source + ": an empty model text (only blanks and line ends)");
  if (path_or_text[first] == '<') return load_xml_string(path_or_text, source);
  return load_yaml_scene_string(path_or_text, source);
}

}  // namespace mbk
