#pragma once
// Always-on invariant checks (also in Release). A broken invariant is a bug in retrace,
// not bad input: it aborts with file and line instead of throwing.

#include <cstdio>
#include <cstdlib>

namespace retrace::core::internal {
[[noreturn]] inline void CheckFailed(const char* expr, const char* file, int line) {
  std::fprintf(stderr, "retrace: internal check failed: %s at %s:%d\n", expr, file, line);
  std::abort();
}
}  // namespace retrace::core::internal

#define RETRACE_CHECK(expr)                                                      \
  do {                                                                           \
    if (!(expr)) ::retrace::core::internal::CheckFailed(#expr, __FILE__, __LINE__); \
  } while (false)
