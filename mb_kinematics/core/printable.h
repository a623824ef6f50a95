// User text inside one-line error messages: control characters (a newline in a name or a
// CSV entry) and bytes that are not UTF-8 written as escapes, so that an error stays one line
// of valid text.
#pragma once

#include <cstdio>
#include <string>

#include "mb_kinematics/core/utf8.h"

namespace mbk {

// `text` with \n, \r, \t, other bytes below 0x20 (and 0x7f) and bytes that are not UTF-8 as
// C escapes (\n, \x01, \xe9).
inline std::string printable(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const unsigned char u = static_cast<unsigned char>(c);
    const size_t n = utf8_length(text, i);
    if (n > 1) {
      out += text.substr(i, n);
      i += n - 1;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f || n == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace mbk
