#include "mb_kinematics/offline/trajectory_csv.h"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mbk {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  for (std::string& c : cells) {
    while (!c.empty() && (c.back() == ' ' || c.back() == '\r')) c.pop_back();
    while (!c.empty() && c.front() == ' ') c.erase(0, 1);
  }
  return cells;
}

}  // namespace

void read_trajectory_csv(const std::string& path, RecordingBuilder& builder) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw std::invalid_argument(path + ": empty file (need a header)");
  const std::vector<std::string> header = split(line);
  if (header.empty() || header[0] != "time")
    throw std::invalid_argument(path +
                                ":1: the first column must be 'time' (then one column "
                                "per coordinate name)");
  const std::vector<std::string> all(header.begin() + 1, header.end());
  std::vector<std::string> names;
  std::vector<double> position;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty() || line == "\r") continue;
    const std::string where = path + ":" + std::to_string(number);
    const std::vector<std::string> cells = split(line);
    if (cells.size() != header.size()) {
      builder.log().drop("wrong number of cells", where + ": " + std::to_string(cells.size()) +
                                                      " cells, header has " +
                                                      std::to_string(header.size()));
      continue;
    }
    names.clear();
    position.clear();
    double t = 0;
    for (size_t i = 0; i < cells.size(); ++i) {
      if (i > 0 && cells[i].empty()) continue;  // not in this sample
      char* end = nullptr;
      const double x = std::strtod(cells[i].c_str(), &end);
      if (cells[i].empty() || *end != '\0')
        throw std::invalid_argument(where + ": column '" + header[i] + "': '" + cells[i] +
                                    "' is not a number");
      if (i == 0) {
        t = x;
      } else {
        names.push_back(all[i - 1]);
        position.push_back(x);
      }
    }
    builder.add(t, names, position, {}, where);
  }
}

}  // namespace mbk
