// Doubles as text that reads back exactly, as short as that allows.
#pragma once

#include <string>

namespace mbk {

// The shortest of %.15g, %.16g, %.17g that reads back as the same double; no "-0".
std::string format_double(double x);

}  // namespace mbk
