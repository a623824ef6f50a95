#include "mb_kinematics/io/text_file.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mbk {

std::string read_text_stream(std::istream& in) {
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string read_text_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open " + what);
  return read_text_stream(in);
}

}  // namespace mbk
