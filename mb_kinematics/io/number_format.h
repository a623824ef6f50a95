// Doubles as text that reads back exactly, as short as that allows.
#pragma once

#include <string>

namespace mbk {

// The shortest of %.15g, %.16g, %.17g that reads back as the same double; no "-0".
std::string format_double(double x);

// The room write_shortest needs at `out`: it writes at most 24 characters and may use the
// bytes after the end it returns as scratch.
constexpr int kMaxDoubleChars = 40;

// Writes at `out` the shortest text that reads back as the same double (std::to_chars; the
// form of the tidy CSV, doc/recorded_data.md), "0" for -0; no allocation. Returns the end.
char* write_shortest(char* out, double x);

}  // namespace mbk
