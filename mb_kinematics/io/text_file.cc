#include "mb_kinematics/io/text_file.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mbk {

std::string read_text_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open " + what);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace mbk
