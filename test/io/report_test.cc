// What `mbk` prints, at the edges: tables of deep chains and of many bodies (aligned, streamed
// row by row), and JSON strings of names with quotes, control characters and bad UTF-8.
#include "mb_kinematics/io/report.h"

#include <gtest/gtest.h>

#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "mb_kinematics/core/lower_body_array.h"

namespace {

std::vector<int> chain(int n) {
  std::vector<int> lower(n);
  for (int i = 0; i < n; ++i) lower[i] = i;
  return lower;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Depth >= 1000 once overflowed the label column's padding (a size_t underflow), and N >= 1000
// ran four-digit entries together. Every entry must sit in its own column.
TEST(LowerBodyTable, DeepChainOfManyBodiesIsAligned) {
  const int n = 1050;
  const std::vector<int> lower = chain(n);
  std::string text;
  ASSERT_NO_THROW(text = mbk::format_lower_body_table(lower));
  const std::vector<std::string> lines = lines_of(text);
  ASSERT_EQ(lines.size(), static_cast<size_t>(n + 2));              // header, t = 0..n
  const size_t label = std::string("L^1050(k) ").size(), cell = 5;  // " 1050"
  for (int t = 0; t <= n; ++t) {
    const std::string& line = lines[t + 1];
    ASSERT_EQ(line.size(), label + cell * n) << "row " << t;
    EXPECT_EQ(line.rfind("L^" + std::to_string(t) + "(k) ", 0), 0u) << line.substr(0, 12);
    for (int k = 1; k <= n; ++k) {
      const std::string entry = line.substr(label + cell * (k - 1), cell);
      const bool shown = t == 0 || mbk::lower_body_power(lower, k, t - 1) != 0;
      const std::string expected = shown ? std::to_string(mbk::lower_body_power(lower, k, t)) : "";
      ASSERT_EQ(entry, std::string(cell - expected.size(), ' ') + expected)
          << "row " << t << ", body " << k;
    }
  }
}

// A stream that takes `limit` bytes and then throws: how far a writer got before giving output.
class LimitedBuffer : public std::streambuf {
 public:
  struct Full {};
  explicit LimitedBuffer(size_t limit) : limit_(limit) {}

 protected:
  int_type overflow(int_type c) override {
    if (++taken_ > limit_) throw Full();
    return c;
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    taken_ += static_cast<size_t>(n);
    if (taken_ > limit_) throw Full();
    return n;
  }

 private:
  size_t limit_, taken_ = 0;
};

// The table of a chain of 30000 bodies is 30001 x 30000 entries (3.6 GB as ints, 4.5 GB as
// text): the writers must emit rows as they compute them, in O(N) memory, not build it first.
TEST(LowerBodyTable, RowsAreStreamed) {
  const std::vector<int> lower = chain(30000);
  for (bool csv : {false, true}) {
    LimitedBuffer buffer(1 << 20);
    std::ostream out(&buffer);
    out.exceptions(std::ios::badbit);
    try {
      if (csv)
        mbk::write_lower_body_csv(out, lower);
      else
        mbk::write_lower_body_table(out, lower);
      ADD_FAILURE() << "the whole table fit in 1 MiB";
    } catch (const LimitedBuffer::Full&) {
    } catch (const std::ios_base::failure&) {  // the stream may wrap Full
    }
  }
}

TEST(LowerBodyTable, StreamedCsvIsTheTable) {
  const std::vector<int> lower = {0, 1, 2, 1, 1, 5, 2, 7, 8, 9};
  std::string expected;
  for (const auto& row : mbk::lower_body_table(lower)) {
    for (size_t i = 0; i < row.size(); ++i) expected += (i ? "," : "") + std::to_string(row[i]);
    expected += "\n";
  }
  std::ostringstream out;
  mbk::write_lower_body_csv(out, lower);
  EXPECT_EQ(out.str(), expected);
  EXPECT_EQ(mbk::format_lower_body_csv(lower), expected);
  EXPECT_EQ(mbk::lower_body_table_rows(lower), 7);
}

TEST(LowerBodyTable, LegendNamesStayOnOneLine) {
  const std::string text = mbk::format_lower_body_table({0, 1}, {"a\nb", "c"});
  EXPECT_NE(text.find("bodies: 1=a\\nb 2=c\n"), std::string::npos) << text;
}

TEST(JsonString, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(mbk::json_string("plain"), "\"plain\"");
  EXPECT_EQ(mbk::json_string("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(mbk::json_string(std::string("n\nt\tz\0e\x1f\x7f", 9)),
            "\"n\\u000at\\u0009z\\u0000e\\u001f\\u007f\"");
}

TEST(JsonString, KeepsUtf8AndReplacesBytesThatAreNot) {
  const std::string utf8 =
      "h\xc3\xbc"
      "fte \xe2\x86\x92 \xf0\x9f\xa6\xb4";  // ü, an arrow, a bone
  EXPECT_EQ(mbk::json_string(utf8), "\"" + utf8 + "\"");
  EXPECT_EQ(mbk::json_string("a\xff"
                             "b"),
            "\"a\\ufffdb\"");                                                // never in UTF-8
  EXPECT_EQ(mbk::json_string("a\xc3"), "\"a\\ufffd\"");                      // cut short
  EXPECT_EQ(mbk::json_string("\xc0\xaf"), "\"\\ufffd\\ufffd\"");             // overlong '/'
  EXPECT_EQ(mbk::json_string("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // a surrogate
}

}  // namespace
