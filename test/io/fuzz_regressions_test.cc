// The inputs the fuzz harnesses (test/fuzz/) once failed on, kept in test/fuzz/regressions/
// <harness>/, replayed in the ordinary build: each loads, or is refused with one
// std::invalid_argument of one line, its user text escaped (doc/reliability.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/state_json.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/io/yaml_scene.h"
#include "test/support/test_models.h"

namespace {

namespace fs = std::filesystem;

// Calls `load` on every file of test/fuzz/regressions/<harness>/ (which must exist); returns how
// many there are.
int replay(const std::string& harness, const std::function<void(const std::string&)>& load) {
  const fs::path dir = mbk_test::source_path("test/fuzz/regressions/" + harness);
  int files = 0;
  EXPECT_TRUE(fs::is_directory(dir)) << dir << ": no such folder of regressions";
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().string());
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    ++files;
    try {
      load(text.str());
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_EQ(mbk::printable(e.what()), e.what());  // user text escaped where it is made
    }
  }
  return files;
}

TEST(FuzzRegressions, StateJson) {
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/human_body.yaml"));
  EXPECT_GT(replay("state_json",
                   [&](const std::string& t) { mbk::read_state_string(model, t, "state.json"); }),
            0);
}

// As the yaml_scene harness: a scene that loads is written as URDF in both styles, and what the
// writer does not refuse must load again (a name that was not UTF-8 once did not).
void yaml_round_trip(const std::string& text) {
  const mbk::Model model = mbk::load_yaml_scene_string(text, "scene.yaml");
  for (const mbk::UrdfStyle style : {mbk::UrdfStyle::kEquivalent, mbk::UrdfStyle::kDisplay}) {
    std::string written;
    try {
      written = mbk::write_urdf(model, "fuzz", style);
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_EQ(mbk::printable(e.what()), e.what());  // user text escaped where it is made
      continue;
    }
    EXPECT_NO_THROW(mbk::load_urdf_string(written, "written.urdf")) << written;
  }
}

TEST(FuzzRegressions, YamlSceneRoundTrip) { EXPECT_GT(replay("yaml_scene", yaml_round_trip), 0); }

}  // namespace
