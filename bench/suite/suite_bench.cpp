#include "bench/suite/suite_bench.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <optional>
#include <set>
#include <system_error>

#include "bench/engine/parallel.hpp"
#include "bench/suite/junit_report.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/trend_file.hpp"
#include "core/errors.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/config_override.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

// The baseline to compare with, read and checked before anything runs. When recording a new
// one, an old baseline is compared with for information if it fits the suite, and another
// suite's baseline is never overwritten.
std::optional<Baseline> PriorBaseline(const BenchRequest& request, const SuiteSpec& spec,
                                      const std::filesystem::path& file) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(file, ec);
  if (!request.update_baseline) {
    if (!exists) {
      throw core::IoError(
          "no baseline " + file.string() + " for suite '" + spec.name +
          "'; record one with `retrace bench " + request.suite.string() + " --update-baseline" +
          (request.baseline.empty() ? "" : " --baseline " + request.baseline.string()) + "`");
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

void RequireOutputFiles(const BenchRequest& request) {
  if (!request.junit.empty()) RequireWritableFile(request.junit, "--junit");
  if (!request.trend.empty()) RequireWritableFile(request.trend, "--trend");
  if (!request.junit.empty() && !request.trend.empty() &&
      std::filesystem::weakly_canonical(request.junit) ==
          std::filesystem::weakly_canonical(request.trend)) {
    throw core::IoError("--junit and --trend name the same file " + request.junit.string());
  }
}

// report.json, report.md, the baseline when recording one, and the CI systems' files.
void WriteResults(const BenchRequest& request, const SuiteSpec& spec, const SuiteResults& results,
                  const SuiteReport& report, const ReportContext& context,
                  const std::filesystem::path& out) {
  io::WriteJsonAtomic(out / "report.json", ReportJson(report, context, spec, results));
  io::WriteFileAtomic(out / "report.md", ReportMarkdown(report, context));
  if (request.update_baseline) WriteBaseline(context.baseline_file, MakeBaseline(spec, results));
  if (!request.junit.empty()) io::WriteFileAtomic(request.junit, JunitXml(report, context));
  if (!request.trend.empty()) io::WriteJsonAtomic(request.trend, TrendJson(report, results));
}

std::string VerdictLine(const SuiteSpec& spec, const SuiteReport& report,
                        const SuiteResults& results, const std::filesystem::path& baseline_file,
                        const Baseline* baseline, bool updated, const std::filesystem::path& out,
                        double wall_time_s, const std::vector<std::string>& only) {
  std::string selection;
  for (const std::string& o : only) selection += (selection.empty() ? " (--only " : ", ") + o;
  if (!selection.empty()) selection += ")";
  const std::string work = std::to_string(spec.entries.size()) +
                           (spec.entries.size() == 1 ? " entry" : " entries") + selection + ", " +
                           std::to_string(results.teaching_drives) + " teaching drives, " +
                           std::to_string(results.playback_runs) + " playback runs, " +
                           core::FixedText(wall_time_s, 1) + " s";
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
void RefuseBaselineWithChanges(const BenchRequest& request) {
  if (request.update_baseline && !request.overrides.empty()) {
    throw core::ConfigError(
        "",
        "--set cannot be combined with --update-baseline: a baseline must be reproducible from "
        "the suite file, so put the override into the entries' `set`",
        true);
  }
  if (request.update_baseline && !request.only.empty()) {
    throw core::ConfigError("",
                            "--only cannot be combined with --update-baseline: a baseline "
                            "covers the whole suite",
                            true);
  }
}

// Each scenario warning of an entry, once however many seeds give it.
void WarnOncePerEntry(const SuiteSpec& spec, const SuiteScenarios& scenarios,
                      ProgressSink* progress) {
  for (std::size_t e = 0; e < spec.entries.size(); ++e) {
    std::set<std::string> seen;
    for (const Scenario& scenario : scenarios.scenarios[e]) {
      for (const std::string& warning : scenario.warnings) {
        if (seen.insert(warning).second) Warn(progress, spec.entries[e].name + ": " + warning);
      }
    }
  }
}

// Where the report's numbers come from.
ReportContext MakeContext(const BenchRequest& request, const SuiteSpec& spec,
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
  context.overrides = request.overrides;
  context.only = request.only;
  context.version = BuildVersion();
  context.recording = request.update_baseline;
  return context;
}

// The suite to run, its baseline and where the report goes, read and checked before anything
// runs.
struct BenchSetup {
  SuiteSpec spec;  ///< the entries and modes run (--only)
  std::filesystem::path baseline_file;
  std::filesystem::path out;
  std::optional<Baseline> baseline;
};

BenchSetup SetUpBench(const BenchRequest& request) {
  RefuseBaselineWithChanges(request);
  RequireOutputFiles(request);
  const SuiteSpec whole = LoadSuiteSpec(request.suite);
  BenchSetup setup;
  setup.baseline_file = request.baseline.empty() ? std::filesystem::path("results") / "baselines" /
                                                       (whole.name + ".json")
                                                 : request.baseline;
  setup.out =
      request.out.empty() ? std::filesystem::path("results") / "bench" / whole.name : request.out;
  setup.baseline = PriorBaseline(request, whole, setup.baseline_file);
  setup.spec = request.only.empty() ? whole : SelectRuns(whole, request.only);
  if (setup.baseline && !request.only.empty())
    setup.baseline = Restricted(std::move(*setup.baseline), setup.spec);
  return setup;
}

}  // namespace

BenchRun RunBench(const BenchRequest& request, ProgressSink* progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : request.overrides) overrides.push_back(io::ParseOverride(text));
  // Everything that can be wrong with the input is found here, before anything runs.
  const BenchSetup setup = SetUpBench(request);
  const SuiteSpec& spec = setup.spec;
  const int jobs = request.jobs > 0 ? request.jobs : DefaultJobs();
  const SuiteScenarios scenarios = LoadSuiteScenarios(spec, overrides, jobs);
  WarnOncePerEntry(spec, scenarios, progress);

  const SuiteResults results = RunSuite(spec, scenarios, jobs, progress);
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const Baseline* compared = setup.baseline ? &*setup.baseline : nullptr;
  BenchRun run{setup.out, CompareWithBaseline(spec, results, compared), {}, 0};
  WriteResults(request, spec, results, run.report,
               MakeContext(request, spec, setup.baseline_file, compared, wall_time, jobs),
               setup.out);
  run.verdict = VerdictLine(spec, run.report, results, setup.baseline_file, compared,
                            request.update_baseline, setup.out, wall_time, request.only);
  run.exit_code = !request.update_baseline && run.report.failures > 0 ? 1 : 0;
  return run;
}

std::string BenchSummary(const BenchRun& run) { return ReportTable(run.report) + run.verdict; }

}  // namespace retrace::bench
