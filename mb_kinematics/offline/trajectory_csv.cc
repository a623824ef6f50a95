#include "mb_kinematics/offline/trajectory_csv.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

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

// A time cell (a number, as strtod read it to `x`) as whole seconds and the fraction after them:
// for decimal text ("1700000000.004000000") each read from its own digits, so that the fraction
// keeps the nanoseconds a double of the whole time would lose; else (an exponent) from x.
struct CellTime {
  double whole, fraction;  // of the same sign
};

CellTime cell_time(const std::string& cell, double x) {
  size_t i = cell[0] == '-' || cell[0] == '+';
  const size_t digits = i;
  while (i < cell.size() && std::isdigit(static_cast<unsigned char>(cell[i]))) ++i;
  const size_t point = i;
  if (i < cell.size() && cell[i] == '.')
    while (++i < cell.size() && std::isdigit(static_cast<unsigned char>(cell[i]))) {
    }
  if (i != cell.size() || !std::isfinite(x)) {  // an exponent (or inf, nan): x is all there is
    const double whole = std::trunc(x);
    return {whole, std::isfinite(x) ? x - whole : 0.0};
  }
  const double sign = cell[0] == '-' ? -1 : 1;
  const double whole =
      point > digits ? std::strtod(cell.substr(digits, point - digits).c_str(), nullptr) : 0.0;
  const double fraction =
      point < cell.size() ? std::strtod(("0" + cell.substr(point)).c_str(), nullptr) : 0.0;
  return {sign * whole, sign * fraction};
}

// Times from this many seconds on (a wall clock's 1.7e9 s, where doubles lie 2.4e-7 s apart) are
// counted from the first one's whole second (Recording::origin); below it a double of the time
// holds its nanoseconds.
constexpr double kTimeOriginFrom = 1e6;

// t as the outputs write it: whole seconds and nanoseconds (io/number_format.h's write_stamp).
std::pair<double, long long> whole_nanoseconds(double t) {
  double whole = std::floor(t);
  long long ns = std::llround((t - whole) * 1e9);
  if (ns == 1000000000) whole += 1, ns = 0;
  return {whole, ns};
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
  double last = std::numeric_limits<double>::quiet_NaN();  // the time of the row before
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
        throw std::invalid_argument(where + ": column '" + printable(header[i]) + "': '" +
                                    printable(cells[i]) + "' is not a number");
      if (i == 0) {  // to the nanosecond, from 1e6 s on after the first whole second
        const CellTime time = cell_time(cells[0], x);
        if (!builder.has_time_origin() && std::isfinite(time.whole))
          builder.set_time_origin(std::abs(time.whole) >= kTimeOriginFrom ? time.whole : 0.0);
        const double origin = builder.time_origin();
        t = origin == 0 ? x : (time.whole - origin) + time.fraction;
        note_rounding(cells[0], builder);
      } else {
        names.push_back(all[i - 1]);
        position.push_back(x);
      }
    }
    if (std::isfinite(t) && t > last && whole_nanoseconds(t) == whole_nanoseconds(last))
      throw std::invalid_argument(where + ": time " + printable(cells[0]) +
                                  " is less than 1 ns after the row before: the outputs' stamps "
                                  "hold whole nanoseconds, so both would be written alike");
    if (std::isfinite(t)) last = t;
    builder.add(t, names, position, {}, where);
  }
}

}  // namespace mbk
