// libFuzzer harness: the URDF loader (mb_kinematics/io/urdf_model.h) on arbitrary text. A URDF
// that loads is evaluated at the zero state (rotations and angular velocities finite) and,
// when `mbk urdf` can write it, what it writes must load again with the same coordinates.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "test/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  mbk::Model model;
  try {
    model = mbk::load_urdf_string(xml, "fuzz.urdf");
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::expect_one_line(e.what());
    return 0;
  }
  mbk_fuzz::expect_finite_kinematics(model, mbk::JointState<double>(model));
  std::string written;
  try {
    written = mbk::write_urdf(model, "fuzz");
  } catch (const std::invalid_argument& e) {  // names URDF cannot hold, clashes
    mbk_fuzz::expect_one_line(e.what());
    return 0;
  }
  try {
    mbk_fuzz::expect_same_coordinates(model, mbk::load_urdf_string(written, "written.urdf"));
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::finding(std::string("written URDF does not load: ") + e.what());
  }
  return 0;
}
