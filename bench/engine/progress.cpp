#include "bench/engine/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"

namespace retrace::bench {

void FinishOrWarn(const char* what, const char* retry, const std::filesystem::path& dir,
                  const std::function<void()>& step, ProgressSink* sink) {
  const auto warn = [&](const char* why) {
    Warn(sink, std::string("no ") + what + ": " + why +
                   " (the results are complete; retry with `retrace " + retry + " " + dir.string() +
                   "`)");
  };
  try {
    step();
  } catch (const core::Error& e) {
    warn(e.what());
  } catch (const std::filesystem::filesystem_error& e) {  // e.g. a figures/ that is a file
    warn(e.what());
  }
}

std::string FormatDuration(double seconds) {
  const long long s = std::llround(std::max(seconds, 0.0));
  char text[48];
  if (s < 60) {
    std::snprintf(text, sizeof(text), "%lld s", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof(text), "%lld min %02lld s", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof(text), "%lld h %02lld min", s / 3600, (s % 3600) / 60);
  }
  return text;
}

}  // namespace retrace::bench
