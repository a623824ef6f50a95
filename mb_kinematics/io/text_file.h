// The whole of a text file, for the loaders of scenes, URDF, MJCF, SDFormat and STATE.json.
#pragma once

#include <istream>
#include <string>

namespace mbk {

// All that is left in the stream (empty if it is at its end).
std::string read_text_stream(std::istream& in);
// Throws std::invalid_argument("<path>: cannot open <what>") if the file cannot be read, and
// refuses what is not a regular file (a link to /dev/zero or a pipe would be read without end).
std::string read_text_file(const std::string& path, const std::string& what);

// True when the first element of the XML text is `element` (after the declaration, comments and
// blanks): tells MJCF (<mujoco>), SDFormat (<sdf>) and URDF (<robot>) apart.
bool xml_root_is(const std::string& xml, const std::string& element);

}  // namespace mbk
