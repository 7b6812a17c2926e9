#pragma once
// Numbers as text for tables, summaries and reports: one fixed-decimal formatter and one
// printf-style formatter, so that no file keeps its own snprintf buffer.

#include <cstdio>
#include <string>

namespace retrace::core {

/// v with exactly `digits` decimals ("%.*f"): FixedText(0.1234, 2) == "0.12".
inline std::string FixedText(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

/// printf's `format` filled with `args` (numbers, C strings), however long the result.
template <class... Args>
std::string Printf(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  if (n <= 0) return {};
  std::string out(static_cast<std::size_t>(n), '\0');
  std::snprintf(out.data(), out.size() + 1, format, args...);
  return out;
}

}  // namespace retrace::core
