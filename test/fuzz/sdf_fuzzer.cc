// libFuzzer harness: the SDFormat reader (mb_kinematics/io/sdformat_reader.cc, linked here
// rather than opened at run time) on arbitrary text, through the system's libsdformat12 (not
// instrumented). A model that loads is evaluated at the zero state (rotations and angular
// velocities finite); one that does not gives one line.
#include <cstddef>
#include <cstdint>
#include <string>

#include "mb_kinematics/io/sdformat_reader.h"
#include "test/fuzz/fuzz_support.h"

extern "C" bool mbk_read_sdformat(const std::string& path_or_text, bool text,
                                  const std::string& source, mbk::Model& model, std::string& error);

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  mbk::Model model;
  std::string error;
  if (!mbk_read_sdformat(xml, true, "fuzz.sdf", model, error)) {
    mbk_fuzz::expect_one_line(error.c_str());
    return 0;
  }
  mbk_fuzz::expect_finite_kinematics(model, mbk::JointState<double>(model));
  return 0;
}
