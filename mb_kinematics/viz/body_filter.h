// Which bodies the picture draws, by name: an inclusion pattern and an exclusion pattern. The
// default inclusion (kDefaultBodyFilter: no "__" in the name) is a plain string test, so no
// name, however long, reaches a regular expression by default. libstdc++'s std::regex matches
// by recursion as deep as the name is long (a name of about 30,000 characters overflows an 8 MB
// stack), so a user's pattern runs only on names of at most kMaxFilteredName characters; a
// longer name is taken as matching neither pattern: not drawn (the count is reported).
#pragma once

#include <cstddef>
#include <optional>
#include <regex>
#include <string>

namespace mbk {

// The default body filter: leaves out the massless links `<body>__<coord>` of ball and free
// joints in URDFs written by `mbk urdf`.
constexpr const char* kDefaultBodyFilter = "^(?!.*__)";
// The longest name a user's regular expression is run on (doc/rviz.md).
constexpr size_t kMaxFilteredName = 1024;

class BodyFilter {
 public:
  // Throws std::regex_error for a pattern that is not an ECMAScript regular expression. An
  // empty `exclude` excludes nothing.
  explicit BodyFilter(const std::string& include = kDefaultBodyFilter,
                      const std::string& exclude = "");
  // Whether a body named `name` is drawn; false for a name too long for a user's pattern.
  bool drawn(const std::string& name) const;
  // Whether `name` is too long for the patterns to be run on it (then it is not drawn).
  bool too_long(const std::string& name) const;

 private:
  bool default_include_;
  std::optional<std::regex> include_, exclude_;
};

}  // namespace mbk
