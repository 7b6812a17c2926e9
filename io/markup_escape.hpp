#pragma once
// The characters that HTML and XML markup must escape, and their entities: the one table behind
// report.html (bench/output/html_report.hpp) and the JUnit XML of `retrace bench`
// (bench/suite/junit_report.hpp). "&#39;" rather than "&apos;": HTML 4 does not know the latter.

namespace retrace::io {

/// The entity that stands for c in markup text and attribute values (& < > " '), or nullptr
/// when c stands for itself.
inline const char* MarkupEntity(char c) {
  switch (c) {
    case '&':
      return "&amp;";
    case '<':
      return "&lt;";
    case '>':
      return "&gt;";
    case '"':
      return "&quot;";
    case '\'':
      return "&#39;";
    default:
      return nullptr;
  }
}

}  // namespace retrace::io
