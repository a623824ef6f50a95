#include "mb_kinematics/io/xacro_markup.h"

#include <cstring>

namespace mbk {
namespace {

bool is_substitution(const char* value) {
  return std::strstr(value, "${") != nullptr || std::strstr(value, "$(") != nullptr;
}

std::string markup_in(const tinyxml2::XMLElement* e) {
  for (; e; e = e->NextSiblingElement()) {
    if (std::strncmp(e->Name(), "xacro:", 6) == 0)
      return std::string("<") + e->Name() + "> at line " + std::to_string(e->GetLineNum());
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
      if (is_substitution(a->Value()))
        return std::string(a->Name()) + "=\"" + a->Value() + "\" at line " +
               std::to_string(e->GetLineNum());
    const std::string inside = markup_in(e->FirstChildElement());
    if (!inside.empty()) return inside;
  }
  return "";
}

}  // namespace

std::string xacro_markup(const tinyxml2::XMLDocument& doc) {
  return markup_in(doc.FirstChildElement());
}

std::string xacro_refusal(const std::string& source, const std::string& markup) {
  // robot_description, or a text given without a file name ("<text>")
  const bool file = source != "robot_description" && (source.empty() || source[0] != '<');
  const std::string name = file ? source : "ROBOT.urdf.xacro";
  return source + ": a xacro document, not a URDF (" + markup + "): expand it first: xacro " +
         name + " > robot.urdf (ROS's xacro package)" +
         (file ? ""
               : ", or load robot_description with <param name=\"robot_description\" "
                 "command=\"xacro " +
                     name + "\"/>");
}

}  // namespace mbk
