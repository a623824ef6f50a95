// mbk urdf's display style: one link per body (no intermediate links), so that rviz's
// RobotModel finds a tf frame for every link when the node runs the scene itself.
#include "mb_kinematics/io/urdf_writer.h"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"
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

}  // namespace
