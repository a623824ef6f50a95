// libFuzzer harness: the YAML scene loader (mb_kinematics/io/yaml_scene.h) on arbitrary text. A
// scene that loads is evaluated at the zero state, and its URDF (both `mbk urdf` styles), when
// written, must load again: with the same coordinates for the equivalent style.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/io/yaml_scene.h"
#include "test/fuzz/fuzz_support.h"

namespace {

void round_trip(const mbk::Model& model, mbk::UrdfStyle style) {
  std::string written;
  try {
    written = mbk::write_urdf(model, "fuzz", style);
  } catch (const std::invalid_argument& e) {  // Euler joints, names URDF cannot hold, clashes
    mbk_fuzz::expect_one_line(e.what());
    return;
  }
  try {
    const mbk::Model back = mbk::load_urdf_string(written, "written.urdf");
    if (style == mbk::UrdfStyle::kEquivalent) mbk_fuzz::expect_same_coordinates(model, back);
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::finding(std::string("written URDF does not load: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mbk::Model model;
  try {
    model = mbk::load_yaml_scene_string(text, "fuzz.yaml");
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::expect_one_line(e.what());
    return 0;
  }
  mbk_fuzz::expect_finite_kinematics(model, mbk::JointState<double>(model));
  round_trip(model, mbk::UrdfStyle::kEquivalent);
  round_trip(model, mbk::UrdfStyle::kDisplay);
  return 0;
}
