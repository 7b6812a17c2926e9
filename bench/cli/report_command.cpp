#include "bench/cli/report_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/output/html_report.hpp"
#include "core/errors.hpp"

namespace retrace::bench {

void AddReportOptions(CLI::App* command, ReportOptions* options) {
  command
      ->add_option("results", options->dir,
                   "Results folder of run, playback, bench, sweep, compare, log-localize or "
                   "log-compare (any folder: the page lists what it holds)")
      ->required();
}

int RunReportCommand(const ReportOptions& options) {
  const HtmlReport report = WriteHtmlReport(options.dir);
  std::cout << "report: " << (options.dir / "report.html").string() << " (" << report.kind << ", "
            << report.images << (report.images == 1 ? " figure" : " figures") << ")\n";
  return 0;
}

void WriteReportAtEnd(const std::filesystem::path& dir) {
  const auto warn = [&](const char* what) {
    std::cerr << "retrace: warning: no report.html: " << what
              << " (the results are complete; retry with `retrace report " << dir.string()
              << "`)\n";
  };
  try {
    WriteHtmlReport(dir);
    std::cout << "report: " << (dir / "report.html").string() << "\n";
  } catch (const core::Error& e) {
    warn(e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    warn(e.what());
  }
}

}  // namespace retrace::bench
