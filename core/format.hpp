#pragma once
// Numbers as text for tables, summaries and reports: one fixed-decimal formatter.

#include <cstdio>
#include <string>

namespace retrace::core {

/// v with exactly `digits` decimals ("%.*f"): FixedText(0.1234, 2) == "0.12".
inline std::string FixedText(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

}  // namespace retrace::core
