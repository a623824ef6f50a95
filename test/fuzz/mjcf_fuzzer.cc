// libFuzzer harness: the MJCF loader (mb_kinematics/io/mjcf_model.h) on arbitrary text, through
// MuJoCo's own compiler (the system's libmujoco, not instrumented). A model that loads is
// evaluated at the zero state (rotations and angular velocities finite); one that does not gives
// one line.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "mb_kinematics/io/mjcf_model.h"
#include "test/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  mbk::Model model;
  try {
    model = mbk::load_mjcf_string(xml, "fuzz.xml");
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::expect_one_line(e.what());
    return 0;
  }
  mbk_fuzz::expect_finite_kinematics(model, mbk::JointState<double>(model));
  return 0;
}
