#include "mb_kinematics/io/bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/number_format.h"
#include "mb_kinematics/io/text_file.h"

namespace mbk {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f'; }
bool is_brace(char c) { return c == '{' || c == '}'; }
// A line ends at LF, CRLF or a lone CR (old Mac exports).
bool is_line_end(char c) { return c == '\n' || c == '\r'; }

// Whitespace-separated tokens of the text, each with its line number, and the text's lines
// (for MOTION's frames, one per line). A UTF-8 byte-order mark at the start is skipped.
class Scanner {
 public:
  Scanner(const std::string& text, const std::string& path)
      : text_(text), path_(path), pos_(text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0) {}

  // `what` may hold the file's names: escaped, as a NUL in one would end what() there.
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw std::invalid_argument(printable(path_ + ":" + std::to_string(line) + ": " + what));
  }
  int line() const { return line_; }

  // The next token, or "" at the end of the text; token_line() is its line.
  std::string next() {
    skip_space();
    token_line_ = line_;
    const size_t begin = pos_;
    if (pos_ < text_.size() && is_brace(text_[pos_])) return text_.substr(pos_++, 1);
    while (pos_ < text_.size() && !is_space(text_[pos_]) && !is_brace(text_[pos_])) ++pos_;
    return text_.substr(begin, pos_ - begin);
  }
  int token_line() const { return token_line_; }

  void expect(const std::string& wanted, const std::string& after) {
    const std::string token = next();
    if (token != wanted)
      fail(token_line_, "expected '" + wanted + "' after " + after + ", got " + quoted(token));
  }

  double number(const std::string& what) {
    const std::string token = next();
    char* end = nullptr;
    const double x = std::strtod(token.c_str(), &end);
    if (token.empty() || *end != '\0' || !std::isfinite(x))
      fail(token_line_, what + ": " + quoted(token) + " is not a number");
    return x;
  }

  int count(const std::string& what, int most) {
    const double x = number(what);
    if (x < 0 || x > most || x != std::floor(x))
      fail(token_line_,
           what + ": " + quoted(text_of(x)) + " is not a count from 0 to " + std::to_string(most));
    return static_cast<int>(x);
  }

  // Moves to the start of the next line that has more than whitespace; false at the end.
  bool next_line() {
    skip_space();
    return pos_ < text_.size();
  }

  // Reads the values of the current line into `row` (exactly row_size of them).
  void frame_values(double* row, int row_size, int frame) {
    int n = 0;
    while (true) {
      while (pos_ < text_.size() && !is_line_end(text_[pos_]) && is_space(text_[pos_])) ++pos_;
      if (pos_ == text_.size() || is_line_end(text_[pos_])) break;
      char* end = nullptr;
      const double x = std::strtod(text_.c_str() + pos_, &end);
      const size_t stop = end - text_.c_str();
      if (stop == pos_ || (stop < text_.size() && !is_space(text_[stop])) || !std::isfinite(x))
        fail(line_, "frame " + std::to_string(frame) + ", value " + std::to_string(n + 1) + ": " +
                        quoted(word_at(pos_)) + " is not a number");
      if (n < row_size) row[n] = x;
      ++n;
      pos_ = stop;
    }
    if (n != row_size)
      fail(line_, "frame " + std::to_string(frame) + " has " + std::to_string(n) +
                      " values, the hierarchy's CHANNELS need " + std::to_string(row_size));
  }

  size_t remaining() const { return text_.size() - pos_; }

  static std::string quoted(const std::string& token) {
    if (token.empty()) return "the end of the file";
    const size_t most = 40;  // keeps the message one short line
    return "'" + (token.size() > most ? token.substr(0, most) + "..." : token) + "'";
  }

 private:
  // Moves past whitespace, counting the line ends (a CRLF once).
  void skip_space() {
    for (; pos_ < text_.size() && is_space(text_[pos_]); ++pos_) {
      const bool crlf = text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n';
      if (is_line_end(text_[pos_]) && !crlf) ++line_;
    }
  }
  static std::string text_of(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }
  std::string word_at(size_t begin) const {
    size_t end = begin;
    while (end < text_.size() && !is_space(text_[end])) ++end;
    return text_.substr(begin, end - begin);
  }

  const std::string& text_;
  const std::string& path_;
  size_t pos_;
  int line_ = 1;
  int token_line_ = 1;
};

BvhChannel channel_named(Scanner& in, const std::string& name) {
  static const char* const kNames[] = {"Xposition", "Yposition", "Zposition",
                                       "Xrotation", "Yrotation", "Zrotation"};
  for (int i = 0; i < 6; ++i)
    if (name == kNames[i]) return static_cast<BvhChannel>(i);
  in.fail(in.token_line(), "unknown channel " + Scanner::quoted(name) +
                               " (Xposition, Yposition, Zposition, Xrotation, Yrotation, "
                               "Zrotation)");
}

Eigen::Vector3d offset(Scanner& in) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = in.number("OFFSET");
  return v;
}

// ROOT or JOINT `keyword`: a new segment under `parent`, its '{' read.
void open_segment(Scanner& in, BvhFile& bvh, const std::string& keyword, int parent) {
  BvhSegment segment;
  segment.name = in.next();
  if (segment.name.empty() || segment.name == "{")
    in.fail(in.token_line(), keyword + " without a name");
  segment.parent = parent;
  segment.line = in.token_line();
  in.expect("{", keyword + " " + segment.name);
  bvh.segments.push_back(segment);
}

void read_channels(Scanner& in, BvhFile& bvh, BvhSegment& segment) {
  const int n = in.count("CHANNELS of " + segment.name, 6);
  segment.channels.clear();
  for (int i = 0; i < n; ++i) segment.channels.push_back(channel_named(in, in.next()));
  segment.first_column = bvh.channel_count;
  bvh.channel_count += n;
}

void read_end_site(Scanner& in, BvhSegment& segment) {
  const std::string where = "End Site of " + segment.name;
  in.expect("Site", "End");
  in.expect("{", where);
  in.expect("OFFSET", where + " {");
  segment.end_site = offset(in);
  segment.has_end_site = true;
  in.expect("}", where + "'s OFFSET");
}

// HIERARCHY up to and including the MOTION keyword. A stack of open segments, not recursion, so
// that a deep hierarchy cannot overflow the call stack.
void read_hierarchy(Scanner& in, BvhFile& bvh) {
  in.expect("HIERARCHY", "the start of the file");
  std::vector<int> open;
  std::vector<int> open_line;
  for (std::string token = in.next();; token = in.next()) {
    const int line = in.token_line();
    const bool inside = !open.empty();
    if (token == "MOTION" || token.empty()) {
      if (inside)
        in.fail(line, "missing '}' of " + bvh.segments[open.back()].name + " (opened at line " +
                          std::to_string(open_line.back()) + ") before " + Scanner::quoted(token));
      if (bvh.segments.empty()) in.fail(line, "empty hierarchy: no ROOT before MOTION");
      if (token.empty()) in.fail(line, "no MOTION section");
      return;
    } else if (token == "ROOT" && !inside && bvh.segments.empty()) {
      open_segment(in, bvh, token, -1);
    } else if (token == "JOINT" && inside) {
      open_segment(in, bvh, token, open.back());
    } else if (token == "OFFSET" && inside) {
      bvh.segments[open.back()].offset = offset(in);
      continue;
    } else if (token == "CHANNELS" && inside) {
      read_channels(in, bvh, bvh.segments[open.back()]);
      continue;
    } else if (token == "End" && inside) {
      read_end_site(in, bvh.segments[open.back()]);
      continue;
    } else if (token == "}" && inside) {
      open.pop_back();
      open_line.pop_back();
      continue;
    } else if (token == "ROOT" && !inside) {
      in.fail(line, "a second ROOT: one skeleton per file is read");
    } else {
      in.fail(line, "unexpected " + Scanner::quoted(token) +
                        (inside ? " inside " + bvh.segments[open.back()].name
                                : std::string(" outside every ROOT")));
    }
    open.push_back(static_cast<int>(bvh.segments.size()) - 1);
    open_line.push_back(line);
  }
}

// A frame time a ROS stamp and duration hold: at least a nanosecond, at most kMaxBvhFrameTime.
void check_frame_time(Scanner& in, double frame_time) {
  if (frame_time <= 0) in.fail(in.token_line(), "Frame Time: must be positive");
  if (frame_time < kMinBvhFrameTime || frame_time > kMaxBvhFrameTime)
    in.fail(in.token_line(), "Frame Time: " + format_double(frame_time) +
                                 " s is not between 1e-9 s (a stamp's nanosecond) and " +
                                 format_double(kMaxBvhFrameTime) + " s (the longest ROS duration)");
}

void read_motion(Scanner& in, BvhFile& bvh) {
  in.expect("Frames:", "MOTION");
  const int declared_line = in.token_line();
  bvh.frame_count = in.count("Frames", 1 << 30);
  in.expect("Frame", "Frames: " + std::to_string(bvh.frame_count));
  in.expect("Time:", "Frame");
  bvh.frame_time = in.number("Frame Time");
  check_frame_time(in, bvh.frame_time);
  if (bvh.channel_count == 0) in.fail(in.token_line(), "the hierarchy has no CHANNELS");
  const size_t wanted = static_cast<size_t>(bvh.frame_count) * bvh.channel_count;
  // n values take at least 2n - 1 characters: a Frames: count larger than the file allocates
  // no more than the file could hold before it is found truncated.
  bvh.frames.resize(std::min(wanted, in.remaining() / 2 + 1));
  for (int f = 0; f < bvh.frame_count; ++f) {
    if (!in.next_line())
      in.fail(in.line(), "truncated MOTION: " + std::to_string(f) + " of the " +
                             std::to_string(bvh.frame_count) + " frames declared at line " +
                             std::to_string(declared_line));
    in.frame_values(bvh.frames.data() + static_cast<size_t>(f) * bvh.channel_count,
                    bvh.channel_count, f);
  }
  bvh.frames.resize(wanted);
  if (in.next_line())
    in.fail(in.line(), "more lines than the " + std::to_string(bvh.frame_count) +
                           " frames declared at line " + std::to_string(declared_line));
}

}  // namespace

bool is_rotation(BvhChannel channel) {
  return channel == BvhChannel::kXrotation || channel == BvhChannel::kYrotation ||
         channel == BvhChannel::kZrotation;
}

BvhFile parse_bvh(const std::string& text, const std::string& path) {
  Scanner in(text, path);
  BvhFile bvh;
  bvh.path = path;
  read_hierarchy(in, bvh);
  read_motion(in, bvh);
  return bvh;
}

BvhFile read_bvh(const std::string& path) {
  return parse_bvh(read_text_file(path, "BVH file"), path);
}

void unwrap_rotations(BvhFile& bvh) {
  for (const BvhSegment& segment : bvh.segments) {
    for (size_t i = 0; i < segment.channels.size(); ++i) {
      if (!is_rotation(segment.channels[i])) continue;
      const int column = segment.first_column + static_cast<int>(i);
      for (int f = 1; f < bvh.frame_count; ++f) {
        const double previous = bvh.value(f - 1, column);
        double& angle = bvh.frames[static_cast<size_t>(f) * bvh.channel_count + column];
        angle -= 360.0 * std::round((angle - previous) / 360.0);
      }
    }
  }
}

}  // namespace mbk
