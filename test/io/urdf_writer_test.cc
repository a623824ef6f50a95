// mbk urdf's display style: one link per body (no intermediate links), so that rviz's
// RobotModel finds a tf frame for every link when the node runs the scene itself.
#include "mb_kinematics/io/urdf_writer.h"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/yaml_scene.h"
#include "test/support/test_models.h"

namespace {

// Body name -> its lower body's name (R's name for 0).
std::map<std::string, std::string> parents(const mbk::Model& model) {
  std::map<std::string, std::string> out;
  for (int k = 1; k <= model.body_count(); ++k)
    out[model.bodies[k].name] = model.bodies[model.bodies[k].lower].name;
  return out;
}

TEST(UrdfWriter, DisplayStyleHasALinkPerBodyAndTheSameTree) {
  for (const char* scene :
       {"config/human_body.yaml", "config/ten_body.yaml", "test/io/data/ball_euler.yaml"}) {
    const mbk::Model model = mbk::load_model_file(mbk_test::source_path(scene));
    const mbk::Model display =
        mbk::load_urdf_string(mbk::write_urdf(model, "display", mbk::UrdfStyle::kDisplay), scene);
    EXPECT_EQ(display.frame, model.frame) << scene;
    EXPECT_EQ(display.body_count(), model.body_count()) << scene;
    EXPECT_EQ(parents(display), parents(model)) << scene;
    for (int k = 1; k <= model.body_count(); ++k) {
      const mbk::Body& b = display.bodies[display.body_index(model.bodies[k].name)];
      EXPECT_EQ(b.joint.offset, model.bodies[k].joint.offset) << scene << " " << b.name;
      EXPECT_LT((b.mass_center - model.bodies[k].mass_center).norm(), 1e-15) << b.name;
    }
  }
}

TEST(UrdfWriter, EquivalentStyleRefusesEulerParameterJoints) {
  const mbk::Model model =
      mbk::load_model_file(mbk_test::source_path("test/io/data/ball_euler.yaml"));
  try {
    mbk::write_urdf(model, "x");
    ADD_FAILURE() << "wrote an Euler-parameter joint as URDF";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no URDF equivalent"), std::string::npos) << e.what();
  }
}

// A URDF's mimic joints are written as mimics (found by the fuzzer: they were dropped).
TEST(UrdfWriter, KeepsMimics) {
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("test/ros/test_robot.urdf"));
  ASSERT_EQ(model.mimics.size(), 1u);
  const mbk::Model back = mbk::load_urdf_string(mbk::write_urdf(model, "r"), "back.urdf");
  ASSERT_EQ(back.mimics.size(), 1u);
  EXPECT_EQ(back.coordinate_names[back.mimics[0].coordinate],
            model.coordinate_names[model.mimics[0].coordinate]);
  EXPECT_EQ(back.coordinate_names[back.mimics[0].source],
            model.coordinate_names[model.mimics[0].source]);
  EXPECT_EQ(back.mimics[0].multiplier, model.mimics[0].multiplier);
  EXPECT_EQ(back.mimics[0].offset, model.mimics[0].offset);
}

// Names with XML's special characters: written escaped, read back as they were.
TEST(UrdfWriter, NamesAreXmlEscaped) {
  const mbk::Model model = mbk::load_yaml_scene_string(
      "frame: \"W<o>rld\"\nbodies:\n"
      "  - {name: 'a\"b', lower: 0, joint: {name: \"j&1\", type: ball_123}}\n"
      "  - {name: \"<c>'\", lower: 1, joint: {name: \"j&amp;2\", type: revolute}}\n",
      "names.yaml");
  for (const auto style : {mbk::UrdfStyle::kEquivalent, mbk::UrdfStyle::kDisplay}) {
    const mbk::Model back =
        mbk::load_urdf_string(mbk::write_urdf(model, "r\"&<'>", style), "names.urdf");
    EXPECT_EQ(back.frame, "W<o>rld");
    for (int k = 1; k <= model.body_count(); ++k)
      EXPECT_GE(back.body_index(model.bodies[k].name), 1) << model.bodies[k].name;
    if (style == mbk::UrdfStyle::kDisplay) {
      EXPECT_EQ(parents(back), parents(model));
    }
    EXPECT_EQ(back.bodies[back.body_index("<c>'")].joint.name, "j&amp;2");
  }
  EXPECT_GE(
      mbk::load_urdf_string(mbk::write_urdf(model, "r"), "names.urdf").coordinate_index("j&1/beta"),
      0);
}

void expect_refused(const std::string& scene, const std::vector<std::string>& fragments) {
  SCOPED_TRACE(scene);
  const mbk::Model model = mbk::load_yaml_scene_string(scene, "scene.yaml");
  try {
    mbk::write_urdf(model, "r");
    ADD_FAILURE() << "wrote a URDF that cannot load";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    for (const std::string& f : fragments)
      EXPECT_NE(what.find(f), std::string::npos) << "'" << f << "' not in: " << what;
  }
}

// XML has no control characters in names (and parsers turn tabs and newlines into spaces).
TEST(UrdfWriter, RefusesNamesWithControlCharacters) {
  expect_refused("bodies:\n  - {name: \"a\\nb\", lower: 0, joint: {type: revolute}}\n",
                 {"'a\\nb'", "control character"});
}

// XML text is Unicode: a name whose bytes are not UTF-8 (here a Latin-1 e-acute run, which a
// fuzzer found) would be written and then not parse. Refused, with the bytes escaped.
TEST(UrdfWriter, RefusesNamesThatAreNotUtf8) {
  expect_refused(
      "bodies:\n  - {name: B1, lower: 0, joint: {name: \"J\xe9\xe9\", type: revolute}}\n",
      {"'J\\xe9\\xe9'", "not UTF-8"});
}

// A name in UTF-8 (here "e-acute" as C3 A9) is written and loads back under the same name.
TEST(UrdfWriter, WritesUtf8Names) {
  const mbk::Model model = mbk::load_yaml_scene_string(
      "bodies:\n  - {name: \"B\xc3\xa9\", lower: 0, joint: {type: revolute}}\n", "utf8.yaml");
  const mbk::Model back =
      mbk::load_urdf_string(mbk::write_urdf(model, "utf8", mbk::UrdfStyle::kEquivalent), "w.urdf");
  ASSERT_EQ(back.bodies.size(), model.bodies.size());
  EXPECT_EQ(back.bodies.back().name, "B\xc3\xa9");
}

// An expanded ball joint makes links <body>__alpha and joints <joint>/alpha, which a scene may
// also use: such a URDF would not load. Refused, naming both owners.
TEST(UrdfWriter, RefusesNameClashesOfExpandedJoints) {
  expect_refused(
      "bodies:\n  - {name: s, lower: 0, joint: {name: j, type: ball_123}}\n"
      "  - {name: s__alpha, lower: s, joint: {name: k, type: fixed}}\n",
      {"link name 's__alpha'", "body 1 's'", "body 2 's__alpha'"});
  expect_refused(
      "bodies:\n  - {name: s, lower: 0, joint: {name: j, type: ball_123}}\n"
      "  - {name: t, lower: s, joint: {name: j/beta, type: fixed}}\n",
      {"joint name 'j/beta'", "body 1 's'", "body 2 't'"});
}

}  // namespace
