#include "mb_kinematics/io/lower_body_text.h"

#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"

namespace mbk {

std::vector<int> parse_lower_body_array(const std::string& text) {
  std::vector<int> lower;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos)
      throw std::invalid_argument("lower body array: entry " + std::to_string(lower.size() + 1) +
                                  " ('" + printable(item) + "') is not an integer");
    lower.push_back(value);
  }
  return lower;
}

}  // namespace mbk
