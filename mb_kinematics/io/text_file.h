// The whole of a text file, for the loaders of scenes, URDF and STATE.json.
#pragma once

#include <istream>
#include <string>

namespace mbk {

// Throws std::invalid_argument("<path>: cannot open <what>") if the file cannot be read.
// All that is left in the stream (empty if it is at its end).
std::string read_text_stream(std::istream& in);
std::string read_text_file(const std::string& path, const std::string& what);

}  // namespace mbk
