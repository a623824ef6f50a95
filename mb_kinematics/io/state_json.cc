#include "mb_kinematics/io/state_json.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <unordered_map>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/text_file.h"

namespace mbk {
namespace {

// Reads one section {name: value} into `out`, where index_of maps a name to its slot.
template <typename IndexOf>
// Names are escaped where they enter a message: a NUL would end what() there.
void read_section(const YAML::Node& root, const char* key, IndexOf index_of, VecX<double>& out) {
  const YAML::Node section = root[key];
  if (!section) return;
  if (!section.IsMap()) throw std::invalid_argument(std::string(key) + " must be an object");
  for (const auto& entry : section) {
    const std::string name = entry.first.Scalar();
    const int i = index_of(name);
    if (i < 0)
      throw std::invalid_argument(std::string(key) + ": unknown coordinate '" + printable(name) +
                                  "'");
    double value = 0;
    try {
      value = entry.second.as<double>();
    } catch (const YAML::Exception&) {
      throw std::invalid_argument(std::string(key) + "." + printable(name) + " is not a number");
    }
    if (!std::isfinite(value))
      throw std::invalid_argument(std::string(key) + "." + printable(name) + " is not finite");
    out[i] = value;
  }
}

// Name -> position, so that a state of N names reads in O(N).
std::unordered_map<std::string, int> name_index(const std::vector<std::string>& names) {
  std::unordered_map<std::string, int> index;
  for (size_t i = 0; i < names.size(); ++i) index.emplace(names[i], static_cast<int>(i));
  return index;
}

int find_index(const std::unordered_map<std::string, int>& index, const std::string& name) {
  const auto it = index.find(name);
  return it == index.end() ? -1 : it->second;
}

JointState<double> parse_state(const Model& model, const std::string& text,
                               const std::string& source) {
  JointState<double> state(model);  // default_state() before its mimics: they follow the text
  try {
    const YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw std::invalid_argument("the state must be a JSON object");
    for (const auto& entry : root) {
      const std::string key = entry.first.Scalar();
      if (key != "position" && key != "velocity" && key != "acceleration")
        throw std::invalid_argument("unknown key '" + printable(key) +
                                    "' (expected position, velocity, acceleration)");
    }
    const auto coordinates = name_index(model.coordinate_names);
    const auto speeds = name_index(model.speed_names);
    auto coordinate = [&](const std::string& n) { return find_index(coordinates, n); };
    auto speed = [&](const std::string& n) { return find_index(speeds, n); };
    read_section(root, "position", coordinate, state.position);
    read_section(root, "velocity", speed, state.velocity);
    read_section(root, "acceleration", speed, state.acceleration);
  } catch (const YAML::DeepRecursion& e) {  // its own message is "bad file"
    throw std::invalid_argument(source + ":" + std::to_string(e.mark.line + 1) +
                                ": malformed JSON: nested " + std::to_string(e.depth()) +
                                " levels deep, too deep to read");
  } catch (const YAML::Exception& e) {
    const std::string line = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1);
    throw std::invalid_argument(source + line + ": malformed JSON: " + e.msg);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
  apply_mimics(model, state);
  return state;
}

}  // namespace

JointState<double> default_state(const Model& model) {
  JointState<double> state(model);
  apply_mimics(model, state);
  return state;
}

// Messages hold names and yaml-cpp's text: control characters escaped to keep them one line.
JointState<double> read_state_string(const Model& model, const std::string& text,
                                     const std::string& source) {
  try {
    return parse_state(model, text, source);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(printable(e.what()));
  }
}

std::size_t state_text_bound(const Model& model) {
  std::size_t most = 1 << 20;
  for (const auto* names : {&model.coordinate_names, &model.speed_names, &model.speed_names})
    for (const std::string& name : *names) most += 6 * name.size() + 64;
  return most;
}

// "-" is standard input, as for other command-line tools; either is read up to the bound only.
JointState<double> read_state_file(const Model& model, const std::string& path) {
  const std::size_t most = state_text_bound(model);
  if (path == "-")
    return read_state_string(model, read_text_stream(std::cin, "standard input", most),
                             "standard input");
  return read_state_string(model, read_text_file(path, "state file", most), path);
}

}  // namespace mbk
