// An unexpanded xacro document where a URDF is expected (a robot_description loaded with
// textfile= instead of command="xacro ...", or a .urdf that is xacro inside): urdfdom would only
// say "No link elements found", so the URDF loader refuses it naming xacro and its command.
#pragma once

#include <tinyxml2.h>

#include <string>

namespace mbk {

// The first xacro markup of the document, as "<xacro:macro> at line 12" or "${...} at line 7"
// (an element in xacro's namespace, or a ${ } / $( ) substitution in an attribute); "" if none.
std::string xacro_markup(const tinyxml2::XMLDocument& doc);

// The one-line refusal of a xacro document read from `source` (a file name or
// "robot_description"): the markup found and the command that expands it.
std::string xacro_refusal(const std::string& source, const std::string& markup);

}  // namespace mbk
