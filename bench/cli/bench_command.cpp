#include "bench/cli/bench_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <set>
#include <system_error>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/engine/parallel.hpp"
#include "bench/suite/baseline.hpp"
#include "bench/suite/junit_report.hpp"
#include "bench/suite/suite_report.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/suite_spec.hpp"
#include "bench/suite/trend_file.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/config_override.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

std::string Seconds(double s) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f s", s);
  return buffer;
}

// The baseline to compare with, read and checked before anything runs. When recording a new
// one, an old baseline is compared with for information if it fits the suite, and another
// suite's baseline is never overwritten.
std::optional<Baseline> PriorBaseline(const BenchOptions& options, const SuiteSpec& spec,
                                      const std::filesystem::path& file) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(file, ec);
  if (!options.update_baseline) {
    if (!exists) {
      throw core::IoError(
          "no baseline " + file.string() + " for suite '" + spec.name +
          "'; record one with `retrace bench " + options.suite.string() + " --update-baseline" +
          (options.baseline.empty() ? "" : " --baseline " + options.baseline.string()) + "`");
    }
    Baseline baseline = ReadBaseline(file);
    CheckBaselineMatches(baseline, spec, file);
    return baseline;
  }
  if (!exists) return std::nullopt;
  std::optional<Baseline> old;
  try {
    old = ReadBaseline(file);
  } catch (const core::IoError&) {
    return std::nullopt;  // a broken baseline is what --update-baseline repairs
  }
  if (old->suite != spec.name) {
    throw core::ConfigError("",
                            file.string() + " is the baseline of suite '" + old->suite +
                                "'; --update-baseline does not overwrite another suite's baseline",
                            true);
  }
  try {
    CheckBaselineMatches(*old, spec, file);
  } catch (const core::ConfigError&) {
    return std::nullopt;  // recorded for other entries: nothing to compare
  }
  return old;
}

// The baseline's metrics and timings of the entries and modes `selected` runs: the others are
// not "no longer computed", only not run this time.
Baseline Restricted(Baseline baseline, const SuiteSpec& selected) {
  std::vector<std::string> prefixes;
  for (const SuiteEntry& entry : selected.entries) {
    for (MapMode mode : entry.modes)
      prefixes.push_back(entry.name + "." + std::string(core::EnumName(mode)) + ".");
  }
  for (auto* table : {&baseline.metrics, &baseline.timing}) {
    std::erase_if(*table, [&](const auto& metric) {
      return std::none_of(prefixes.begin(), prefixes.end(), [&](const std::string& prefix) {
        return metric.first.starts_with(prefix);
      });
    });
  }
  return baseline;
}

// An output file of the command line (--junit, --trend), checked before anything runs so that
// a bad path fails now, not after the runs: not a folder, and the nearest folder on its way that
// exists is one this process may create files in (the missing ones are made when it is written).
void RequireWritableFile(const std::filesystem::path& file, const std::string& option) {
  const std::string what = option + " " + file.string();
  std::error_code ec;
  const std::string name = file.filename().string();
  if (name.empty() || name == "." || name == ".." || std::filesystem::is_directory(file, ec))
    throw core::IoError(what + ": is a folder, not a file");
  std::filesystem::path folder = std::filesystem::absolute(file, ec).parent_path();
  while (!std::filesystem::exists(folder, ec) && folder.has_relative_path())
    folder = folder.parent_path();
  if (!std::filesystem::is_directory(folder, ec))
    throw core::IoError(what + ": cannot write there: " + folder.string() + " is not a folder");
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw core::IoError(what + ": cannot write in " + folder.string() + ": " +
                        std::generic_category().message(errno));
  }
}

void RequireOutputFiles(const BenchOptions& options) {
  if (!options.junit.empty()) RequireWritableFile(options.junit, "--junit");
  if (!options.trend.empty()) RequireWritableFile(options.trend, "--trend");
  if (!options.junit.empty() && !options.trend.empty() &&
      std::filesystem::weakly_canonical(options.junit) ==
          std::filesystem::weakly_canonical(options.trend)) {
    throw core::IoError("--junit and --trend name the same file " + options.junit.string());
  }
}

// report.json, report.md, the baseline when recording one, and the CI systems' files.
void WriteResults(const BenchOptions& options, const SuiteSpec& spec, const SuiteResults& results,
                  const SuiteReport& report, const ReportContext& context,
                  const std::filesystem::path& out) {
  io::WriteJsonAtomic(out / "report.json", ReportJson(report, context, spec, results));
  io::WriteFileAtomic(out / "report.md", ReportMarkdown(report, context));
  if (options.update_baseline) WriteBaseline(context.baseline_file, MakeBaseline(spec, results));
  if (!options.junit.empty()) io::WriteFileAtomic(options.junit, JunitXml(report, context));
  if (!options.trend.empty()) io::WriteJsonAtomic(options.trend, TrendJson(report, results));
}

std::string VerdictLine(const SuiteSpec& spec, const SuiteReport& report,
                        const SuiteResults& results, const std::filesystem::path& baseline_file,
                        const Baseline* baseline, bool updated, const std::filesystem::path& out,
                        double wall_time_s, const std::vector<std::string>& only) {
  std::string selection;
  for (const std::string& o : only) selection += (selection.empty() ? " (--only " : ", ") + o;
  if (!selection.empty()) selection += ")";
  const std::string work =
      std::to_string(spec.entries.size()) + (spec.entries.size() == 1 ? " entry" : " entries") +
      selection + ", " + std::to_string(results.teaching_drives) + " teaching drives, " +
      std::to_string(results.playback_runs) + " playback runs, " + Seconds(wall_time_s);
  std::string line = "suite " + spec.name + ": ";
  if (updated) {
    line += "baseline written to " + baseline_file.string() + " (" +
            std::to_string(report.checked) + " gated metrics";
    if (baseline != nullptr) {
      line += "; against the old one: " + std::to_string(report.failures) + " worse, " +
              std::to_string(report.improved) + " improved";
    }
    return line + "); " + work;
  }
  if (report.failures > 0) {
    line += "FAIL: " + std::to_string(report.failures) + " of " + std::to_string(report.checked) +
            " metrics regressed (";
    int listed = 0;
    for (const ReportRow& row : report.rows) {
      if (!IsFailure(row.check.verdict)) continue;
      if (listed == 3) {
        line += ", ...";
        break;
      }
      line += (listed++ ? ", " : "") + row.name;
    }
    return line + ") against " + baseline_file.string() + "; report in " +
           (out / "report.md").string() + "; " + work;
  }
  return line + "pass: " + std::to_string(report.checked) + " metrics within tolerance of " +
         baseline_file.string() + " (git " + baseline->git_revision + ", " + baseline->date +
         "), " + std::to_string(report.improved) + " improved, " + std::to_string(report.reported) +
         " reported; " + work;
}

// --set and --only against --update-baseline: a baseline is the whole suite as its file says.
void RefuseBaselineWithChanges(const BenchOptions& options) {
  if (options.update_baseline && !options.overrides.empty()) {
    throw core::ConfigError(
        "",
        "--set cannot be combined with --update-baseline: a baseline must be reproducible from "
        "the suite file, so put the override into the entries' `set`",
        true);
  }
  if (options.update_baseline && !options.only.empty()) {
    throw core::ConfigError("",
                            "--only cannot be combined with --update-baseline: a baseline "
                            "covers the whole suite",
                            true);
  }
}

// Each scenario warning of an entry, once however many seeds give it.
void WarnOncePerEntry(const SuiteSpec& spec, const SuiteScenarios& scenarios) {
  for (std::size_t e = 0; e < spec.entries.size(); ++e) {
    std::set<std::string> seen;
    for (const Scenario& scenario : scenarios.scenarios[e]) {
      for (const std::string& warning : scenario.warnings) {
        if (seen.insert(warning).second)
          std::cerr << "retrace: warning: " << spec.entries[e].name << ": " << warning << "\n";
      }
    }
  }
}

// Where the report's numbers come from.
ReportContext MakeContext(const BenchOptions& options, const SuiteSpec& spec,
                          const std::filesystem::path& baseline_file, const Baseline* compared,
                          double wall_time, int jobs) {
  ReportContext context;
  context.suite_file = spec.source;
  context.suite_digest = spec.digest;
  context.baseline_file = baseline_file;
  context.baseline = compared;
  context.git_revision = BuildRevision();
  context.date = UtcNow();
  context.wall_time_s = wall_time;
  context.jobs = jobs;
  context.overrides = options.overrides;
  context.only = options.only;
  context.version = BuildVersion();
  context.recording = options.update_baseline;
  return context;
}

}  // namespace

void AddBenchOptions(CLI::App* command, BenchOptions* options) {
  command->add_option("suite", options->suite, "Suite file (YAML), e.g. bench/suites/ci.yaml")
      ->required();
  command->add_option("--baseline", options->baseline,
                      "Baseline file (default: results/baselines/<suite name>.json)");
  command->add_flag("--update-baseline", options->update_baseline,
                    "Record the results as the suite's baseline instead of judging them");
  AddJobsOption(command, &options->jobs);
  AddOutOption(command, &options->out, "Report folder (default: results/bench/<suite name>)");
  AddSetOption(command, &options->overrides, "a scenario key in every entry: a.b.c=value");
  command->add_option("--only", options->only,
                      "Run and judge only these entries or modes: <entry>[.<mode>] (repeatable)");
  command->add_option("--junit", options->junit,
                      "Write the verdicts as JUnit XML to FILE: a testcase per gated metric, a "
                      "failure per regression (also written on a regression)");
  command->add_option("--trend", options->trend,
                      "Write every metric of the run to FILE as Bencher Metric Format JSON, "
                      "for trend charts across commits");
  AddNoReportFlag(command, &options->report,
                  "Do not write report.html, the report's page with the regressions in red, "
                  "also written on a regression (retrace report does it later)");
}

int RunBenchCommand(const BenchOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : options.overrides) overrides.push_back(io::ParseOverride(text));
  RefuseBaselineWithChanges(options);

  // Everything that can be wrong with the input is found here, before anything runs.
  RequireOutputFiles(options);
  const SuiteSpec whole = LoadSuiteSpec(options.suite);
  const std::filesystem::path baseline_file =
      options.baseline.empty()
          ? std::filesystem::path("results") / "baselines" / (whole.name + ".json")
          : options.baseline;
  const std::filesystem::path out =
      options.out.empty() ? std::filesystem::path("results") / "bench" / whole.name : options.out;
  std::optional<Baseline> baseline = PriorBaseline(options, whole, baseline_file);
  const SuiteSpec spec = options.only.empty() ? whole : SelectRuns(whole, options.only);
  if (baseline && !options.only.empty()) baseline = Restricted(std::move(*baseline), spec);
  const int jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
  const SuiteScenarios scenarios = LoadSuiteScenarios(spec, overrides, jobs);
  WarnOncePerEntry(spec, scenarios);

  ProgressLine progress;
  const SuiteResults results = RunSuite(spec, scenarios, jobs, &progress);
  progress.Clear();
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const Baseline* compared = baseline ? &*baseline : nullptr;
  const SuiteReport report = CompareWithBaseline(spec, results, compared);
  WriteResults(options, spec, results, report,
               MakeContext(options, spec, baseline_file, compared, wall_time, jobs), out);
  std::cout << ReportTable(report)
            << VerdictLine(spec, report, results, baseline_file, compared, options.update_baseline,
                           out, wall_time, options.only)
            << "\n";
  if (options.report) WriteReportAtEnd(out);
  return !options.update_baseline && report.failures > 0 ? 1 : 0;
}

}  // namespace retrace::bench
