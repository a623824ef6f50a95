// Facts read straight from URDF text (tinyxml2, not urdfdom), for tests that check the loader
// and the node against the file itself.
#pragma once

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <string>

namespace mbk_test {

// The sum of every link's <inertial><mass value>: the robot's total mass as the URDF states it.
inline double urdf_mass_sum(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS);
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  double sum = 0;
  for (auto* link = robot ? robot->FirstChildElement("link") : nullptr; link;
       link = link->NextSiblingElement("link")) {
    const auto* inertial = link->FirstChildElement("inertial");
    const auto* mass = inertial ? inertial->FirstChildElement("mass") : nullptr;
    if (mass) sum += mass->DoubleAttribute("value");
  }
  return sum;
}

// A root link of 15.36 kg (its mass center off its origin) and one 2.5 kg leg on a hinge.
constexpr char kHeavyRootUrdf[] =
    "<robot name=\"q\"><link name=\"base\"><inertial><origin xyz=\"0.1 -0.02 0.05\"/>"
    "<mass value=\"15.36\"/><inertia ixx=\"0.3\" ixy=\"0\" ixz=\"0\" iyy=\"0.4\" iyz=\"0\" "
    "izz=\"0.5\"/></inertial></link><link name=\"leg\"><inertial><origin xyz=\"0 0 -0.2\"/>"
    "<mass value=\"2.5\"/><inertia ixx=\"0.02\" ixy=\"0\" ixz=\"0\" iyy=\"0.02\" iyz=\"0\" "
    "izz=\"0.01\"/></inertial></link><joint name=\"hip\" type=\"continuous\"><parent "
    "link=\"base\"/><child link=\"leg\"/><origin xyz=\"0.3 0 0\"/><axis xyz=\"0 1 0\"/></joint>"
    "</robot>";

}  // namespace mbk_test
