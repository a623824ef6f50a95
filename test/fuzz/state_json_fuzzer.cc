// libFuzzer harness: STATE.json (mb_kinematics/io/state_json.h) on arbitrary text, for the human
// body model (1-2-3 angles, a free joint) and an Euler-parameter scene. A state that loads and
// that check_state accepts gives finite kinematics and `mbk eval` JSON without an error.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/io/state_json.h"
#include "test/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mbk::Model models[] = {
      mbk::load_model_file(mbk_fuzz::source_path("config/human_body.yaml")),
      mbk::load_model_file(mbk_fuzz::source_path("test/io/data/ball_euler.yaml"))};
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const mbk::Model& model : models) {
    mbk::JointState<double> state(model);
    try {
      state = mbk::read_state_string(model, text, "fuzz.json");
    } catch (const std::invalid_argument& e) {
      mbk_fuzz::expect_one_line(e.what());
      continue;
    }
    if (!mbk::check_state(model, state).empty()) continue;
    mbk::Data<double> kinematics(model);
    mbk::forward_kinematics(model, state, kinematics);
    try {
      mbk::format_eval_json(model, kinematics);
    } catch (const std::exception& e) {
      mbk_fuzz::finding(std::string("a state check_state accepts gives no JSON: ") + e.what());
    }
  }
  return 0;
}
