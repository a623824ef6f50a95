// A BVH file's text with joints renamed, for skeletons of other naming conventions (or lacking
// a segment: hands renamed paws) from one shipped file.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mbk_test {

// The text of the BVH file at `path` with every joint named `from` (a whole name at a line's
// end, "JOINT LeftHand") named `to`, for each pair of `names`.
inline std::string renamed(const std::string& path,
                           const std::vector<std::pair<std::string, std::string>>& names) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  for (const auto& [from, to] : names)
    for (size_t at = text.find(" " + from + "\n"); at != std::string::npos;
         at = text.find(" " + from + "\n", at + 1))
      text.replace(at + 1, from.size(), to);
  return text;
}

}  // namespace mbk_test
