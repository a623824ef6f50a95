#include "mb_kinematics/viz/body_filter.h"

namespace mbk {

BodyFilter::BodyFilter(const std::string& include, const std::string& exclude)
    : default_include_(include == kDefaultBodyFilter) {
  if (!default_include_) include_.emplace(include);
  if (!exclude.empty()) exclude_.emplace(exclude);
}

bool BodyFilter::too_long(const std::string& name) const {
  return (include_ || exclude_) && name.size() > kMaxFilteredName;
}

bool BodyFilter::drawn(const std::string& name) const {
  if (too_long(name)) return false;
  if (default_include_ && name.find("__") != std::string::npos) return false;
  if (include_ && !std::regex_search(name, *include_)) return false;
  return !(exclude_ && std::regex_search(name, *exclude_));
}

}  // namespace mbk
