#include "bench/replay/log_run_options.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "io/config_override.hpp"

namespace retrace::bench {

void RequireWindow(const LogWindow& window) {
  if (!(window.from_s >= 0.0) || !std::isfinite(window.from_s))
    throw core::ConfigError("--from",
                            "must be a time >= 0 s, got " + core::FormatNumber(window.from_s));
  if (!(window.to_s > window.from_s)) {
    throw core::ConfigError("--to", "must be later than --from: got --to " +
                                        core::FormatNumber(window.to_s) + " s, --from " +
                                        core::FormatNumber(window.from_s) + " s");
  }
}

LogConfig LoadLogRunConfig(const LogRunOptions& options, const std::vector<std::string>& extra) {
  RequireWindow(options.window);
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : options.overrides) overrides.push_back(io::ParseOverride(text));
  if (options.seed) overrides.push_back(io::ParseOverride("seed=" + std::to_string(*options.seed)));
  for (const std::string& text : extra) overrides.push_back(io::ParseOverride(text));
  return LoadLogConfig(options.config, overrides);
}

}  // namespace retrace::bench
