#pragma once
// `retrace log-compare <log-localize folders>... --out DIR`: their metrics in one table and
// their errors in one figure (bench/replay/log_comparison.hpp), e.g. real scans against the same
// log simulated.

#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogCompareOptions {
  std::vector<std::filesystem::path> runs;
  std::vector<std::string> labels;
  std::filesystem::path out;
};

void AddLogCompareOptions(CLI::App* cmd, LogCompareOptions* options);

/// Writes DIR/comparison.md and DIR/errors.png (the folder is staged) and prints the table;
/// returns 0. Throws core::Error for bad input, before anything is written.
int RunLogCompareCommand(const LogCompareOptions& options);

}  // namespace retrace::bench
