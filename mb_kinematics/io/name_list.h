// Names in one line of a message: "a, b, c". ROS-free.
#pragma once

#include <string>
#include <vector>

namespace mbk {

inline std::string name_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace mbk
