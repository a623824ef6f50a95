// User text inside one-line error messages: control characters (a newline in a name or a
// CSV entry) written as escapes, so that an error stays one line.
#pragma once

#include <cstdio>
#include <string>

namespace mbk {

// `text` with \n, \r, \t and other bytes below 0x20 (and 0x7f) as C escapes (\n, \x01).
inline std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
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
