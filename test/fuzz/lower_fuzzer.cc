// libFuzzer harness: `mbk tables --lower` (parse_lower_body_array, validate_lower_body_array and
// the streamed table writers) on arbitrary text. A valid array's text table has one line per row
// plus the header, and its CSV one line per row.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/core/lower_body_array.h"
#include "mb_kinematics/io/lower_body_text.h"
#include "mb_kinematics/io/report.h"
#include "test/fuzz/fuzz_support.h"

namespace {

size_t lines(const std::string& text) {
  size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<int> lower;
  try {
    lower = mbk::parse_lower_body_array(text);
    mbk::validate_lower_body_array(lower);
  } catch (const std::invalid_argument& e) {
    mbk_fuzz::expect_one_line(e.what());
    return 0;
  }
  const size_t rows = static_cast<size_t>(mbk::lower_body_table_rows(lower));
  std::ostringstream table, csv;
  mbk::write_lower_body_table(table, lower);
  mbk::write_lower_body_csv(csv, lower);
  if (lines(table.str()) != rows + 1 || lines(csv.str()) != rows)
    mbk_fuzz::finding("table rows do not match the depth");
  return 0;
}
