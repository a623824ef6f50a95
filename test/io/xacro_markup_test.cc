// An unexpanded xacro document where a URDF is expected (io/xacro_markup.h): the URDF loader
// refuses it in one line naming xacro, the markup it found and the command that expands it,
// instead of urdfdom's "No link elements found".
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"

namespace {

// A small robot as its xacro source: a property and a macro, used once.
const char* const kXacro =
    "<?xml version=\"1.0\"?>\n"
    "<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
    "  <xacro:property name=\"length\" value=\"0.3\"/>\n"
    "  <xacro:macro name=\"segment\" params=\"name\">\n"
    "    <link name=\"${name}\"/>\n"
    "  </xacro:macro>\n"
    "  <link name=\"base\"/>\n"
    "  <xacro:segment name=\"upper\"/>\n"
    "</robot>\n";

std::string error_of(const std::string& xml, const std::string& source) {
  try {
    mbk::load_urdf_string(xml, source);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(XacroMarkup, RobotDescriptionNamesXacroAndTheCommand) {
  const std::string m = error_of(kXacro, "robot_description");
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  EXPECT_EQ(
      m.rfind("robot_description: a xacro document, not a URDF (<xacro:property> at line 3)", 0),
      0u)
      << m;
  EXPECT_NE(m.find("xacro ROBOT.urdf.xacro > robot.urdf"), std::string::npos) << m;
  EXPECT_NE(m.find("command=\"xacro ROBOT.urdf.xacro\""), std::string::npos) << m;
  EXPECT_EQ(m.find("No link elements"), std::string::npos) << m;
}

TEST(XacroMarkup, SubstitutionAloneIsXacro) {  // no xacro: element, a ${} in an attribute
  const std::string m = error_of(
      "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"${prefix}b\"/>\n</robot>", "<text>");
  EXPECT_NE(m.find("<text>: a xacro document, not a URDF (name=\"${prefix}b\" at line 3)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("xacro ROBOT.urdf.xacro > robot.urdf"), std::string::npos) << m;
}

TEST(XacroMarkup, UrdfFileNamesItsPathInTheCommand) {  // xacro inside a file named .urdf
  char path[] = "/tmp/mbk_xacro_XXXXXX.urdf";
  const int fd = mkstemps(path, 5);
  ASSERT_GE(fd, 0);
  close(fd);
  std::ofstream(path) << kXacro;
  std::string m;
  try {
    mbk::load_model_file(path);
  } catch (const std::invalid_argument& e) {
    m = e.what();
  }
  std::remove(path);
  EXPECT_NE(m.find(std::string(path) + ": a xacro document"), std::string::npos) << m;
  EXPECT_NE(m.find(std::string("expand it first: xacro ") + path + " > robot.urdf"),
            std::string::npos)
      << m;
}

TEST(XacroMarkup, ExpandedUrdfWithTheNamespaceLoads) {  // what xacro writes keeps xmlns:xacro
  const mbk::Model m = mbk::load_urdf_string(
      "<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">"
      "<link name=\"base\"/><link name=\"upper\"/>"
      "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"upper\"/>"
      "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>",
      "robot_description");
  EXPECT_EQ(m.body_count(), 1);
}

}  // namespace
