#include "mb_kinematics/offline/trajectory_csv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/text_file.h"

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

// The next line, whatever ends it: LF, CRLF or a lone CR (old Mac exports); false at the end.
bool next_line(std::istream& in, std::string& line) {
  line.clear();
  std::streambuf& buf = *in.rdbuf();  // not istream::get(): a sentry per character
  constexpr int kEof = std::char_traits<char>::eof();
  int c = buf.sbumpc();
  if (c == kEof) return false;
  for (; c != kEof && c != '\n' && c != '\r'; c = buf.sbumpc())
    line.push_back(static_cast<char>(c));
  if (c == '\r' && buf.sgetc() == '\n') buf.sbumpc();
  return true;
}

// The header's cells (a UTF-8 byte-order mark before it skipped); a name given twice is an error.
std::vector<std::string> read_header(std::istream& in, const std::string& path) {
  std::string line;
  if (!next_line(in, line)) throw std::invalid_argument(path + ": empty file (need a header)");
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  const std::vector<std::string> header = split(line);
  if (header.empty() || header[0] != "time")
    throw std::invalid_argument(path +
                                ":1: the first column must be 'time' (then one column "
                                "per coordinate name)");
  std::unordered_map<std::string, size_t> first;  // name -> its column: linear in the columns
  first.reserve(header.size());
  for (size_t i = 0; i < header.size(); ++i) {
    const auto [it, inserted] = first.emplace(header[i], i);
    if (!inserted)
      throw std::invalid_argument(path + ":1: column '" + header[i] + "' is given twice (" +
                                  std::to_string(it->second + 1) + " and " + std::to_string(i + 1) +
                                  ")");
  }
  return header;
}

// A time written in decimals ("12.345678") is off its true value by up to half a unit of its
// last decimal: a grid is allowed three quarters of a unit (the half, and the least-squares
// line's own error), and a stamp a whole unit off is not on it. One in exponent form says
// nothing here.
void note_rounding(const std::string& time, RecordingBuilder& builder) {
  if (time.find_first_of("eE") != std::string::npos) return;
  const size_t point = time.find('.');
  const size_t decimals = point == std::string::npos ? 0 : time.size() - point - 1;
  builder.note_stamp_rounding(0.75 * std::pow(10.0, -static_cast<double>(decimals)));
}

}  // namespace

void read_trajectory_csv(const std::string& path, RecordingBuilder& builder) {
  check_regular_file(path, "the recording");  // a pipe or /dev/zero would be read without end
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot open");
  const std::vector<std::string> header = read_header(in, path);
  std::string line;
  const std::vector<std::string> all(header.begin() + 1, header.end());
  std::vector<std::string> names;
  std::vector<double> position;
  for (int number = 2; next_line(in, line); ++number) {
    if (line.empty()) continue;
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
      if (cells[i].empty() || end != cells[i].c_str() + cells[i].size())  // a NUL inside too
        throw std::invalid_argument(where + ": column '" + header[i] + "': '" +
                                    printable(cells[i]) + "' is not a number");
      if (i == 0) {
        t = x;
        note_rounding(cells[0], builder);
      } else {
        names.push_back(all[i - 1]);
        position.push_back(x);
      }
    }
    builder.add(t, names, position, {}, where);
  }
}

}  // namespace mbk
