#include "mb_kinematics/io/yaml_bare_scene.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"

namespace mbk {
namespace {

[[noreturn]] void fail(int line, const std::string& what) {
  throw std::invalid_argument(std::to_string(line + 1) + ": " + printable(what));
}

// Thrown at the first event a plain bare scene does not have: the node tree reads the text.
struct NotBare {};

// The events of a plain bare scene.
class BareSceneEvents : public YAML::EventHandler {
 public:
  bool seen_map = false, has_array = false;
  std::map<std::string, std::pair<std::string, int>> scalars;  // key -> value, line
  int array_line = 0;
  std::vector<int> lower;
  std::string entry_error;  // the first bad entry's, reported after the scalars' checks
  int entry_error_line = 0;

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override { throw NotBare(); }
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { throw NotBare(); }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    if (anchor != YAML::NullAnchor || (tag != "?" && tag != "!") || depth_ == 0) throw NotBare();
    if (depth_ == 1 && !has_key_) {  // a key
      if (!keys_.insert(value).second || value == "bodies") throw NotBare();
      key_ = value, has_key_ = true;
    } else if (depth_ == 1) {                           // a key's scalar value
      if (key_ == "lower_body_array") throw NotBare();  // not a list: the tree's error
      scalars[key_] = {value, mark.line};
      has_key_ = false;
    } else if (depth_ == 2 && in_array_) {
      add_entry(mark.line, value);
    }  // else inside another key's value: not read
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, true);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, false);
  }
  void OnMapEnd() override { close(); }

 private:
  void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool sequence) {
    if (anchor != YAML::NullAnchor || (depth_ == 0 && sequence)) throw NotBare();
    if (depth_ == 0) seen_map = true;
    if (depth_ == 1) {
      // A key that is not a scalar, or one of these that is not a scalar: the tree's reading.
      if (!has_key_ || key_ == "frame" || key_ == "speeds" || key_ == "joint_type" ||
          (key_ == "lower_body_array" && !sequence))
        throw NotBare();
      in_array_ = key_ == "lower_body_array";
      if (in_array_) has_array = true, array_line = mark.line;
    }
    if (depth_ >= 2 && in_array_) throw NotBare();  // a list or map as an entry
    ++depth_;
  }
  void close() {
    if (--depth_ == 1) in_array_ = false, has_key_ = false;
  }
  void add_entry(int line, const std::string& value) {
    if (!entry_error.empty()) return;
    double x = 0;
    try {
      x = YAML::Node(value).as<double>();  // as the tree's read_number
    } catch (const YAML::Exception&) {
      entry_error = "lower_body_array must be a number, not '" + value + "'";
    }
    if (entry_error.empty() && !std::isfinite(x)) entry_error = "lower_body_array is not finite";
    if (entry_error.empty() && (x != std::floor(x) || std::abs(x) > 1e9))
      entry_error = "lower_body_array entry '" + value + "' is not an integer";
    if (!entry_error.empty()) entry_error_line = line;
    if (entry_error.empty()) lower.push_back(static_cast<int>(x));
  }

  int depth_ = 0;
  bool in_array_ = false, has_key_ = false;
  std::string key_;
  std::set<std::string> keys_;
};

}  // namespace

bool read_bare_scene(const std::string& text, Model& model) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  BareSceneEvents events;
  try {
    parser.HandleNextDocument(events);
  } catch (const NotBare&) {
    return false;
  }
  if (!events.seen_map || !events.has_array) return false;
  const auto scalar = [&](const char* key) { return events.scalars.find(key); };
  if (scalar("frame") != events.scalars.end() && scalar("frame")->second.first.empty())
    fail(scalar("frame")->second.second, "frame must be a name");
  if (scalar("speeds") != events.scalars.end()) {
    const std::string& speeds = scalar("speeds")->second.first;
    if (speeds != "angular_velocity" && speeds != "coordinate_derivatives")
      fail(scalar("speeds")->second.second,
           "speeds must be coordinate_derivatives or angular_velocity, not '" + speeds + "'");
  }
  if (!events.entry_error.empty()) fail(events.entry_error_line, events.entry_error);
  const auto type = scalar("joint_type");
  try {
    model = make_bare_model(
        events.lower,
        joint_type_from_string(type == events.scalars.end() ? "ball_123" : type->second.first));
  } catch (const std::invalid_argument& e) {
    fail(events.array_line, e.what());
  }
  return true;
}

}  // namespace mbk
