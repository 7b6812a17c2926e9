#pragma once
// `retrace report <results dir>`: writes <dir>/report.html, one self-contained page of the
// folder's summary tables, figures, comparison, suite regressions, sweep table and manifests
// (bench/output/html_report.hpp). `run`, `playback`, `bench`, `sweep` and `compare` write it
// at their end unless given --no-report.

#include <filesystem>
#include <functional>

namespace CLI {
class App;
}

namespace retrace::bench {

struct ReportOptions {
  std::filesystem::path dir;
};

/// Adds the command's arguments to a CLI11 subcommand.
void AddReportOptions(CLI::App* command, ReportOptions* options);

/// `retrace render <dir>`: the figures of a results folder again.
struct RenderOptions {
  std::filesystem::path dir;
};
void AddRenderOptions(CLI::App* command, RenderOptions* options);
int RunRenderCommand(const RenderOptions& options);

/// Writes the page and prints "report: <file> (<n> figures)" on stdout. Returns 0. Throws
/// core::IoError (nothing written) when the folder does not exist, is not a folder, or holds an
/// unreadable manifest or results file.
int RunReportCommand(const ReportOptions& options);

/// The end of a command that wrote a results folder: writes its report.html and prints
/// "report: <file>" on stdout; a failure is a warning on stderr, never an error (the results are
/// complete without the page).
void WriteReportAtEnd(const std::filesystem::path& dir);

}  // namespace retrace::bench
