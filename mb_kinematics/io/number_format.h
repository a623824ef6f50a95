// Doubles as text that reads back exactly, as short as that allows: the form of the tidy CSV
// (doc/recorded_data.md), of the URDF writer and of the reports; and to a number of significant
// digits (the error bars' side files).
#pragma once

#include <string>

namespace mbk {

// The room write_shortest and write_general need at `out` (they write at most 24 characters).
constexpr int kMaxDoubleChars = 32;

// Writes at `out` the shortest text that reads back as the same double, as std::to_chars(first,
// last, x) writes it (fixed or scientific, whichever is shorter), "0" for -0; no allocation.
// Returns the end. Where the standard library has no std::to_chars for double (GCC 9, ROS
// Noetic): the shortest of %.15g, %.16g, %.17g that reads back.
char* write_shortest(char* out, double x);

// Writes at `out` the text of printf's %.*g (precision significant digits, at most 17), as an
// ostream at that precision writes it; no allocation. Returns the end.
char* write_general(char* out, double x, int precision);

// The room write_stamp needs at `out`.
constexpr int kMaxStampChars = 400;

// Writes at `out` the time origin + t in seconds with 9 decimals, rounded to the nanosecond, as
// %.9f of the exact sum would: `origin` whole seconds (a recording's, offline/recording.h) and t
// the seconds after it, so that a wall-clock stamp (1.7e9 s) keeps its nanoseconds, which a
// double of it would not. Returns the end.
char* write_stamp(char* out, double origin, double t);

// The double write_stamp's text reads back as: the stamp as every output holds it (the tidy CSV's
// and the OpenSim file's text, the HDF5 file's time), so that they agree number for number.
double written_stamp(double origin, double t);

// write_shortest's text as a string.
std::string format_double(double x);

}  // namespace mbk
