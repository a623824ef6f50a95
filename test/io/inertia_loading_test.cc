// Inertias I_k: YAML `inertia: [ixx, iyy, izz, ixy, ixz, iyz]` about G_k in Bk's
// axes, URDF <inertial> with its origin rpy turned into Bk's axes, and `mbk urdf` writing them
// back; bad inertias are one-line errors naming the file, line (YAML), body and field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mb_kinematics/core/inertia.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/io/yaml_scene.h"

namespace {

using M = mbk::Mat3<double>;

std::string scene(const std::string& inertia) {
  return "frame: R\nbodies:\n  - {name: B1, lower: 0, joint: {type: ball_123}, mass: 2}\n"
         "  - {name: B2, lower: 1, joint: {type: revolute, axis: [0, 0, 1]}, mass: 1,\n"
         "     inertia: " +
         inertia + "}\n";
}

std::string yaml_error(const std::string& text) {
  try {
    mbk::load_yaml_scene_string(text, "scene.yaml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(Inertia, YamlInertiaIsTheMatrixOfItsSixComponents) {
  const mbk::Model model = mbk::load_yaml_scene_string(scene("[1, 2, 2.5, 0.1, -0.2, 0.3]"), "s");
  EXPECT_FALSE(model.bodies[1].has_inertia);
  ASSERT_TRUE(model.bodies[2].has_inertia);
  M expected;
  expected << 1, 0.1, -0.2, 0.1, 2, 0.3, -0.2, 0.3, 2.5;
  EXPECT_EQ(model.bodies[2].inertia, expected);
}

TEST(Inertia, YamlErrorsNameFileLineBodyAndField) {
  struct Case {
    const char* inertia;
    const char* what;
  };
  for (const Case& c : {Case{"[1, 2, 3]", "must be a list of 6 numbers"},
                        Case{"[1, 2, 3, 0, 0, x]", "must be a number, not 'x'"},
                        Case{"[1, 2, .inf, 0, 0, 0]", "is not finite"},
                        Case{"[-1, 2, 2, 0, 0, 0]", "not positive semidefinite"},
                        Case{"[1, 1, 3, 0, 0, 0]", "triangle inequality"},
                        Case{"[1, 1, 1, 2, 0, 0]", "not positive semidefinite"}}) {
    const std::string message = yaml_error(scene(c.inertia));
    SCOPED_TRACE(c.inertia);
    EXPECT_EQ(message.rfind("scene.yaml:5: ", 0), 0u) << message;
    EXPECT_NE(message.find("body 2 'B2' inertia"), std::string::npos) << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(Inertia, ChecksOfThePrincipalMoments) {
  EXPECT_EQ(mbk::inertia_problem(M::Zero()), "");                              // a point mass
  EXPECT_EQ(mbk::inertia_problem(mbk::inertia_matrix(0, 1, 1, 0, 0, 0)), "");  // a thin rod
  EXPECT_EQ(mbk::inertia_problem(mbk::inertia_matrix(1, 1, 2, 0, 0, 0)), "");  // a thin disk
  EXPECT_NE(mbk::inertia_problem(mbk::inertia_matrix(1, 1, 2.001, 0, 0, 0)), "");
  M asymmetric = M::Identity();
  asymmetric(0, 1) = 0.1;
  EXPECT_EQ(mbk::inertia_problem(asymmetric), "is not symmetric");
}

std::string urdf(const std::string& inertial_origin, const std::string& inertia) {
  return "<robot name=\"r\"><link name=\"base\"/><link name=\"arm\"><inertial>" + inertial_origin +
         "<mass value=\"2\"/><inertia " + inertia +
         "/></inertial></link><joint name=\"j\" type=\"continuous\"><parent link=\"base\"/>"
         "<child link=\"arm\"/><axis xyz=\"0 0 1\"/></joint></robot>";
}

// The inertia about G_k in the <inertial> origin's axes, turned into Bk's: R I R^T.
TEST(Inertia, UrdfInertialRpyIsTurnedIntoTheBodyAxes) {
  const char diag123[] = "ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"3\"";
  const mbk::Model plain = mbk::load_urdf_string(urdf("", diag123), "r.urdf");
  ASSERT_TRUE(plain.bodies[1].has_inertia);
  EXPECT_TRUE(plain.warnings.empty());
  EXPECT_EQ(plain.bodies[1].inertia, M(mbk::Vec3<double>(1, 2, 3).asDiagonal()));
  const mbk::Model turned = mbk::load_urdf_string(
      urdf("<origin xyz=\"0.1 0 0\" rpy=\"0 0 1.5707963267948966\"/>", diag123), "r.urdf");
  EXPECT_LT((turned.bodies[1].inertia - M(mbk::Vec3<double>(2, 1, 3).asDiagonal())).norm(), 1e-15);
  // A general rpy: the principal moments stay, the axes turn.
  const mbk::Model general =
      mbk::load_urdf_string(urdf("<origin rpy=\"0.3 -0.7 1.1\"/>", diag123), "r.urdf");
  const M r = (Eigen::AngleAxisd(1.1, mbk::Vec3<double>::UnitZ()) *
               Eigen::AngleAxisd(-0.7, mbk::Vec3<double>::UnitY()) *
               Eigen::AngleAxisd(0.3, mbk::Vec3<double>::UnitX()))
                  .toRotationMatrix();
  EXPECT_LT(
      (general.bodies[1].inertia - r * mbk::Vec3<double>(1, 2, 3).asDiagonal() * r.transpose())
          .norm(),
      1e-14);
}

// Inertias that are not physical (a sensor mount, a 1e-6 kg antenna) never stop a URDF
// from loading: those bodies keep no inertia (H_G is left out) and one warning names every link.
TEST(Inertia, UrdfUnphysicalInertiasLoadWithOneWarningNamingEveryLink) {
  const std::string xml =
      "<robot name=\"r\"><link name=\"base\"/>"
      "<link name=\"mount\"><inertial><mass value=\"1\"/><inertia ixx=\"0.001\" ixy=\"0\" "
      "ixz=\"0\" iyy=\"0.001\" iyz=\"0\" izz=\"0.01\"/></inertial></link>"
      "<link name=\"antenna\"><inertial><mass value=\"1e-6\"/><inertia ixx=\"-3.5e-08\" "
      "ixy=\"0\" ixz=\"0\" iyy=\"1e-7\" iyz=\"0\" izz=\"1e-7\"/></inertial></link>"
      "<link name=\"arm\"><inertial><mass value=\"2\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" "
      "iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>"
      "<joint name=\"j1\" type=\"fixed\"><parent link=\"base\"/><child link=\"mount\"/></joint>"
      "<joint name=\"j2\" type=\"fixed\"><parent link=\"mount\"/><child link=\"antenna\"/>"
      "</joint><joint name=\"j3\" type=\"continuous\"><parent link=\"base\"/>"
      "<child link=\"arm\"/><axis xyz=\"0 0 1\"/></joint></robot>";
  const mbk::Model model = mbk::load_urdf_string(xml, "r.urdf");
  EXPECT_FALSE(model.bodies[model.body_index("mount")].has_inertia);
  EXPECT_FALSE(model.bodies[model.body_index("antenna")].has_inertia);
  EXPECT_TRUE(model.bodies[model.body_index("arm")].has_inertia);
  EXPECT_EQ(model.bodies[model.body_index("antenna")].mass, 1e-6);  // the mass stays
  ASSERT_EQ(model.warnings.size(), 1u);
  const std::string& w = model.warnings[0];
  EXPECT_EQ(w.rfind("r.urdf: ", 0), 0u) << w;
  EXPECT_NE(w.find("angular momentum is left out"), std::string::npos) << w;
  EXPECT_NE(w.find("'mount' inertia violates the triangle inequality I1 + I2 >= I3 (principal "
                   "moments 0.001, 0.001, 0.01)"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("'antenna' inertia is not positive semidefinite (principal moments -3.5e-08"),
            std::string::npos)
      << w;
  EXPECT_EQ(w.find('\n'), std::string::npos) << w;
}

// `mbk urdf` writes a scene's inertias; without one it writes the token URDF needs, marked, and
// the loader reads it back as no inertia: nothing is invented.
TEST(Inertia, WrittenUrdfKeepsInertiasAndInventsNone) {
  const mbk::Model model =
      mbk::load_yaml_scene_string(scene("[1, 2, 2.5, 0.1, -0.2, 0.3]"), "s.yaml");
  const std::string xml = mbk::write_urdf(model, "r");
  EXPECT_NE(xml.find(mbk::kTokenInertia), std::string::npos);  // B1 has none
  const mbk::Model back = mbk::load_urdf_string(xml, "r.urdf");
  const int b1 = back.body_index("B1"), b2 = back.body_index("B2");
  ASSERT_GT(b1, 0);
  ASSERT_GT(b2, 0);
  EXPECT_FALSE(back.bodies[b1].has_inertia);
  EXPECT_EQ(back.bodies[b1].mass, 2.0);
  ASSERT_TRUE(back.bodies[b2].has_inertia);
  EXPECT_EQ(back.bodies[b2].inertia, model.bodies[2].inertia);  // printed to round trip
  for (int k = 1; k <= back.body_count(); ++k) {  // the massless links of the expanded ball joint
    if (back.bodies[k].mass == 0) {
      EXPECT_FALSE(back.bodies[k].has_inertia) << back.bodies[k].name;
    }
  }
}

}  // namespace
