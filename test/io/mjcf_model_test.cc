// The MJCF loader's mapping and errors (io/mjcf_model.h); that the models move as MuJoCo moves
// them is test/peers/mujoco_test.cc.
#include "mb_kinematics/io/mjcf_model.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "mb_kinematics/io/load_model.h"
#include "test/support/temp_file.h"
#include "test/support/test_models.h"

namespace {

std::string error_of(const std::function<void()>& load) {
  try {
    load();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

const char kTwoJoints[] = R"(<mujoco><compiler angle="radian"/><worldbody>
  <body name="a" pos="0 0 1">
    <inertial mass="2" pos="0.1 0 0" diaginertia="1 1 1"/>
    <joint name="ax" type="hinge" axis="1 0 0"/>
    <joint name="ay" type="hinge" axis="0 1 0" pos="0 0 0.5" ref="0.3"/>
    <body name="b" pos="1 0 0"><inertial mass="1" pos="0 0 0" diaginertia="1 1 1"/></body>
    <body pos="0 1 0"><inertial mass="1" pos="0 0 0" diaginertia="1 1 1"/>
      <joint type="slide" axis="0 0 1"/></body>
  </body></worldbody></mujoco>)";

TEST(MjcfModel, BodiesKeepTheirNamesAndHoldTheirMass) {
  const mbk::Model model = mbk::load_mjcf_string(kTwoJoints);
  EXPECT_EQ(model.frame, "world");
  // a's joints: ax at a's origin (a massless body a__ax), ay with its anchor off a's origin (a
  // massless body a__ay at the anchor, then a on a fixed joint); b welded to a; body 3 unnamed.
  std::vector<std::string> names;
  for (int k = 1; k <= model.body_count(); ++k) names.push_back(model.bodies[k].name);
  EXPECT_EQ(names, (std::vector<std::string>{"a__ax", "a__ay", "a", "b", "body3"}));
  EXPECT_EQ(model.lower_body_array(), (std::vector<int>{0, 1, 2, 3, 3}));
  EXPECT_EQ(model.bodies[3].joint.type, mbk::JointType::kFixed);
  EXPECT_EQ(model.bodies[1].mass, 0.0);
  EXPECT_EQ(model.bodies[2].mass, 0.0);
  EXPECT_EQ(model.bodies[3].mass, 2.0);
  EXPECT_EQ(model.coordinate_names, (std::vector<std::string>{"ax", "ay", "joint2"}));
}

TEST(MjcfModel, BallAndFreeJointsNameTheirCoordinates) {
  const mbk::Model model =
      mbk::load_mjcf_file(mbk_test::source_path("test/robots/mjcf/humanoid.xml"));
  ASSERT_GE(model.coordinate_index("root/x"), 0);
  EXPECT_EQ(model.coordinate_index("root/e4"), model.coordinate_index("root/x") + 6);
  EXPECT_GT(model.body_index("torso"), 0);
  EXPECT_EQ(model.nq, 28);  // as MuJoCo: 7 of the free joint, 21 hinges
}

TEST(MjcfModel, AnUnnamedFreeJointIsJointIdAsInMujoco) {
  // Menagerie's Robotis OP3: <freejoint/> without a name (MuJoCo's joint 0), 20 named hinges.
  const mbk::Model op3 = mbk::load_mjcf_file(mbk_test::source_path("test/robots/mjcf/op3.xml"));
  ASSERT_EQ(op3.coordinate_index("joint0/x"), 0);
  EXPECT_EQ(op3.coordinate_index("joint0/e4"), 6);
  EXPECT_EQ(op3.coordinate_index("head_pan"), 7);
  EXPECT_EQ(op3.nq, 27);  // as MuJoCo: 7 of the free joint, 20 hinges
  EXPECT_EQ(op3.body_count(), 21);
  EXPECT_EQ(op3.bodies[op3.body_index("body_link")].mass, 1.34928);
}

TEST(MjcfModel, LinearJointEqualitiesAreMimicsOthersAWarning) {
  const mbk::Model panda = mbk::load_mjcf_file(mbk_test::source_path("test/robots/mjcf/panda.xml"));
  ASSERT_EQ(panda.mimics.size(), 1u);
  EXPECT_EQ(panda.mimics[0].coordinate, panda.coordinate_index("finger_joint1"));
  EXPECT_EQ(panda.mimics[0].source, panda.coordinate_index("finger_joint2"));
  EXPECT_EQ(panda.mimics[0].multiplier, 1.0);
  EXPECT_EQ(panda.mimics[0].offset, 0.0);
  EXPECT_TRUE(panda.warnings.empty());

  std::string text = kTwoJoints;
  text.replace(text.find("</mujoco>"), 9,
               R"(<equality><connect name="loop" body1="a" body2="b" anchor="0 0 0"/>
                  <joint joint1="ay" joint2="ax" polycoef="0.1 2 0.5 0 0"/></equality></mujoco>)");
  const mbk::Model model = mbk::load_mjcf_string(text, "coupled.xml");
  EXPECT_TRUE(model.mimics.empty());
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_NE(model.warnings[0].find("coupled.xml: equality constraints left out"),
            std::string::npos);
  EXPECT_NE(model.warnings[0].find("connect 'loop', joint '#1'"), std::string::npos)
      << model.warnings[0];
}

TEST(MjcfModel, XmlFilesAndTextGoByTheirFirstElement) {
  const std::string mjcf = mbk_test::write_temp(kTwoJoints, "model.xml");
  EXPECT_EQ(mbk::load_model_file(mjcf).body_count(), 5);
  EXPECT_EQ(mbk::load_model(std::string("<?xml version=\"1.0\"?><!-- <robot> -->\n") + kTwoJoints)
                .body_count(),
            5);
  const std::string urdf = mbk_test::write_temp(
      "<robot name=\"r\"><link name=\"base\"/><link name=\"l\"/><joint name=\"j\" "
      "type=\"continuous\"><parent link=\"base\"/><child link=\"l\"/></joint></robot>",
      "robot.xml");
  EXPECT_EQ(mbk::load_model_file(urdf).frame, "base");
}

TEST(MjcfModel, ErrorsAreOneLineNamingTheFile) {
  const std::string bad = mbk_test::write_temp(
      "<mujoco><worldbody><body name=\"x\"><joint/></body>"
      "</worldbody></mujoco>",
      "massless.xml");
  const std::string e = error_of([&] { mbk::load_model_file(bad); });
  EXPECT_NE(e.find("massless.xml: MuJoCo refuses the model: Error: mass and inertia of moving "
                   "bodies must be larger than mjMINVAL"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;

  const std::string mesh = mbk_test::write_temp(
      "<mujoco><asset><mesh name=\"m\" file=\"nowhere/link.stl\"/></asset><worldbody><body>"
      "<joint/><geom type=\"mesh\" mesh=\"m\"/></body></worldbody></mujoco>",
      "meshes.xml");
  const std::string m = error_of([&] { mbk::load_model_file(mesh); });
  EXPECT_NE(m.find("meshes.xml: MuJoCo refuses the model: Error: could not open STL file"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("nowhere/link.stl'"), std::string::npos) << m;
  EXPECT_NE(m.find("kinematics does not need meshes"), std::string::npos) << m;

  EXPECT_NE(error_of([] {
              mbk::load_mjcf_string("<mujoco><worldbod", "cut.xml");
            }).find("cut.xml: MuJoCo refuses the model: XML parse error"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              mbk::load_model_file("/nonexistent/robot.xml");
            }).find("/nonexistent/robot.xml: cannot open"),
            std::string::npos);
}

}  // namespace
