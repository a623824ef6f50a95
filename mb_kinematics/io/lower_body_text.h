// A lower body array as text (`mbk tables --lower`).
#pragma once

#include <string>
#include <vector>

namespace mbk {

// Parses "0,1,2,1" (spaces allowed) into a lower body array; throws std::invalid_argument
// naming the bad entry. The result is not validated: call validate_lower_body_array.
std::vector<int> parse_lower_body_array(const std::string& text);

}  // namespace mbk
