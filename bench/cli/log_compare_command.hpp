#pragma once
// `retrace log-compare <log-localize folders>... --out DIR`: the options of
// bench/calibration/log_compare_run.hpp's CompareLogs, which it calls; writes their metrics in
// one table and their errors in one figure (WriteLogCompareFolder), e.g. real scans against the
// same log simulated, and prints its summary.

#include "bench/calibration/log_compare_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

struct LogCompareOptions {
  LogCompareRequest request;
};

void AddLogCompareOptions(CLI::App* cmd, LogCompareOptions* options);

/// Writes DIR/comparison.md and DIR/errors.png (the folder is staged) and prints the table;
/// returns 0. Throws core::Error for bad input, before anything is written.
int RunLogCompareCommand(const LogCompareOptions& options);

}  // namespace retrace::bench
