// A file of the test's own under gtest's temporary folder.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace mbk_test {

// Writes `text` to `name` in ::testing::TempDir() and returns its path.
inline std::string write_temp(const std::string& text, const std::string& name) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace mbk_test
