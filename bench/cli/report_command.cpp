#include "bench/cli/report_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/progress.hpp"
#include "bench/output/html_report.hpp"
#include "bench/output/render_results.hpp"
#include "core/errors.hpp"

namespace retrace::bench {

void AddReportOptions(CLI::App* command, ReportOptions* options) {
  command
      ->add_option("results", options->dir,
                   "Results folder of run, playback, bench, sweep, compare, log-localize or "
                   "log-compare (any folder: the page lists what it holds)")
      ->required();
}

void AddRenderOptions(CLI::App* command, RenderOptions* options) {
  command
      ->add_option("results", options->dir, "Results folder of `retrace run` (results/<scenario>)")
      ->required();
}

int RunRenderCommand(const RenderOptions& options) {
  const auto files = RenderResults(options.dir);
  std::cout << files.size() << " figures in " << options.dir.string() << "\n";
  return 0;
}

int RunReportCommand(const ReportOptions& options) {
  const HtmlReport report = WriteHtmlReport(options.dir);
  std::cout << "report: " << (options.dir / "report.html").string() << " (" << report.kind << ", "
            << report.images << (report.images == 1 ? " figure" : " figures") << ")\n";
  return 0;
}

void WriteReportAtEnd(const std::filesystem::path& dir) {
  ProgressLine warnings;
  FinishOrWarn(
      "report.html", "report", dir,
      [&] {
        WriteHtmlReport(dir);
        std::cout << "report: " << (dir / "report.html").string() << "\n";
      },
      &warnings);
}

}  // namespace retrace::bench
