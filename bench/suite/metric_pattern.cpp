#include "bench/suite/metric_pattern.hpp"

#include <cctype>

namespace retrace::bench {

bool MatchMetricPattern(std::string_view pattern, std::string_view name) {
  // Glob matching by backtracking over the two wildcards. Names and patterns are short (under
  // a hundred characters, a handful of stars), so the worst case does not matter.
  if (pattern.empty()) return name.empty();
  if (pattern.substr(0, 2) == "**") {
    const std::string_view rest = pattern.substr(2);
    for (std::size_t skip = 0; skip <= name.size(); ++skip) {
      if (MatchMetricPattern(rest, name.substr(skip))) return true;
    }
    return false;
  }
  if (pattern.front() == '*') {
    const std::string_view rest = pattern.substr(1);
    for (std::size_t skip = 0; skip <= name.size(); ++skip) {
      if (MatchMetricPattern(rest, name.substr(skip))) return true;
      if (skip < name.size() && name[skip] == '.') break;  // one star stays inside a dotted part
    }
    return false;
  }
  return !name.empty() && name.front() == pattern.front() &&
         MatchMetricPattern(pattern.substr(1), name.substr(1));
}

std::string PatternProblem(std::string_view pattern) {
  if (pattern.empty()) return "empty pattern";
  for (char c : pattern) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_' && c != '-' && c != '.' &&
        c != '*') {
      return std::string("unexpected character '") + c +
             "' (patterns use letters, digits, _ - . * **)";
    }
  }
  if (pattern.find("***") != std::string_view::npos) return "'***' is not a wildcard; use * or **";
  if (pattern.front() == '.' || pattern.back() == '.' ||
      pattern.find("..") != std::string_view::npos) {
    return "empty dotted part";
  }
  return "";
}

int DecidingPattern(const std::vector<std::string>& patterns, std::string_view name) {
  for (std::size_t i = patterns.size(); i-- > 0;) {
    if (MatchMetricPattern(patterns[i], name)) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace retrace::bench
