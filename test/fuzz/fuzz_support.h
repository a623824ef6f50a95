// Shared by the fuzz harnesses (doc/reliability.md): what every input must give. Bad input is
// one std::invalid_argument with a one-line message; anything else (another exception, a crash,
// a sanitizer report, a leak) is a finding: the harness aborts so that libFuzzer keeps it.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/state_check.h"

namespace mbk_fuzz {

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "mbk fuzz finding: %s\n", what.c_str());
  std::abort();
}

// The message of a refused input: one line, not empty, its user text escaped.
inline void expect_one_line(const char* what) {
  const std::string message = what;
  if (message.empty() || message.find('\n') != std::string::npos)
    finding("error message not one line: '" + message + "'");
  if (mbk::printable(message) != message)  // user text is escaped where the message is made
    finding("error message with raw control bytes: '" + mbk::printable(message) + "'");
}

// The kinematics of a loaded model at a state that check_state accepts: all finite.
inline void expect_finite_kinematics(const mbk::Model& model,
                                     const mbk::JointState<double>& state) {
  if (!mbk::check_state(model, state).empty()) return;
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  for (int k = 1; k <= model.body_count(); ++k)
    if (!data.rotation[k].allFinite() || !data.omega[k].allFinite() || !data.alpha[k].allFinite())
      finding("rotation or angular velocity of body " + std::to_string(k) + " not finite");
}

// What `mbk urdf` must keep of a model: its coordinate names (the numbering may differ: URDF
// numbers breadth-first, through the links of expanded joints) and its mimics.
inline void expect_same_coordinates(const mbk::Model& a, const mbk::Model& b) {
  std::vector<std::string> names_a = a.coordinate_names, names_b = b.coordinate_names;
  std::sort(names_a.begin(), names_a.end());
  std::sort(names_b.begin(), names_b.end());
  if (names_a != names_b || a.mimics.size() != b.mimics.size())
    finding("written URDF has other coordinates or mimics");
}

// The source tree (for the models the STATE.json and JointState harnesses use).
inline std::string source_path(const std::string& relative) {
  return std::string(MBK_SOURCE_DIR) + "/" + relative;
}

}  // namespace mbk_fuzz
