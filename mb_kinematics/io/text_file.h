// The whole of a text file, for the loaders of scenes, URDF, MJCF, SDFormat and STATE.json.
#pragma once

#include <cstddef>
#include <istream>
#include <limits>
#include <string>

namespace mbk {

// All that is left in the stream (empty if it is at its end).
std::string read_text_stream(std::istream& in);
// The same, refused with std::invalid_argument("<source>: more than <most> bytes ...") as soon
// as it holds more than `most` bytes (standard input fed by `yes` or /dev/zero ends there).
std::string read_text_stream(std::istream& in, const std::string& source, std::size_t most);
// Throws std::invalid_argument("<path>: cannot open <what>") if the file cannot be read, and
// refuses what is not a regular file (a link to /dev/zero or a pipe would be read without end)
// and a file of more than `most` bytes.
std::string read_text_file(const std::string& path, const std::string& what,
                           std::size_t most = std::numeric_limits<std::size_t>::max());
// Throws as read_text_file unless `path` names a regular file that can be opened, for readers
// that open it themselves (a trajectory CSV, a bag, a segment map). A name holding a NUL byte is
// refused (the file named by what comes before it would be read); a pipe is not waited on.
void check_regular_file(const std::string& path, const std::string& what);

// True when the first element of the XML text is `element` (after the declaration, comments and
// blanks): tells MJCF (<mujoco>), SDFormat (<sdf>) and URDF (<robot>) apart.
bool xml_root_is(const std::string& xml, const std::string& element);

}  // namespace mbk
