#include "bench/cli/sweep_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/engine/parallel.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/scheduler.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/sweep/sweep_folder.hpp"
#include "bench/sweep/sweep_plan.hpp"
#include "bench/sweep/sweep_results.hpp"
#include "bench/sweep/sweep_summary.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
#include "git_revision.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A row read back from results.csv must be the row this sweep would write for its case:
// anything else means the folder holds another sweep's results.
void CheckRow(const SweepPlan& plan, const SweepShard& shard, const SweepRow& row,
              const std::filesystem::path& file) {
  const SweepSpec& s = plan.spec;
  const std::size_t id = row.case_id;
  const std::string where =
      file.string() + ":" + std::to_string(row.line_number) + ": case " + std::to_string(id);
  if (id >= s.case_count())
    throw core::IoError(where + ": the sweep has only " + std::to_string(s.case_count()) +
                        " cases");
  if (!shard.Contains(id)) throw core::IoError(where + ": not a case of shard " + shard.ToString());
  const std::size_t c = plan.combination(id);
  std::vector<std::string> expected = {std::to_string(c), std::to_string(plan.repeat(id)),
                                       std::to_string(plan.seed(id))};
  expected.insert(expected.end(), s.combinations[c].begin(), s.combinations[c].end());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (row.fields[1 + i] != expected[i]) {
      throw core::IoError(where + ": " + ResultsSchema(s.parameters, s.metrics).header[1 + i] +
                          " is '" + row.fields[1 + i] + "', this sweep has '" + expected[i] + "'");
    }
  }
}

struct FolderState {
  SweepTable results;
  SweepTable timings;
};

// What an existing results folder holds, checked against this sweep and shard. Writes nothing.
FolderState InspectFolder(const std::filesystem::path& out, const SweepPlan& plan,
                          const SweepShard& shard) {
  FolderState state;
  if (!std::filesystem::exists(out)) return state;
  auto another = [&](const std::string& why) {
    return core::ConfigError("--out",
                             out.string() + " holds results of another sweep (" + why +
                                 "); use another --out or remove it",
                             true);
  };
  const std::filesystem::path results_file = out / "results.csv";
  if (std::filesystem::exists(out / "sweep.json")) {
    const SweepRecord record = ReadSweepRecord(out / "sweep.json");
    if (record.identity != plan.identity) {
      throw another("'" + record.name + "' with identity " + record.identity +
                    "; this sweep's is " + plan.identity);
    }
    if (record.shard.index != shard.index || record.shard.count != shard.count) {
      throw another("shard " + record.shard.ToString() + "; this is shard " + shard.ToString());
    }
  } else if (std::filesystem::exists(results_file)) {
    throw another("a results.csv without sweep.json");
  }
  const SweepSpec& s = plan.spec;
  state.results =
      ReadSweepTable(results_file, ResultsSchema(s.parameters, s.metrics), PartialRow::kDrop);
  for (const SweepRow& row : state.results.rows) CheckRow(plan, shard, row, results_file);
  state.timings =
      ReadSweepTable(out / "timings.csv", TimingsSchema(s.timing_metrics), PartialRow::kDrop);
  return state;
}

// The rows of one finished case.
struct CaseOutput {
  std::vector<io::CsvCell> results;
  std::vector<io::CsvCell> timings;
};

// The rows of case `id` from its metrics; `wall_time_s` from the start of its scenario's loading
// to the end of its run.
CaseOutput CaseRows(const SweepPlan& plan, std::size_t id,
                    const std::map<std::string, double>& metrics, double wall_time_s) {
  const SweepSpec& s = plan.spec;
  const std::size_t c = plan.combination(id);
  auto metric = [&metrics](const std::string& name) {
    const auto it = metrics.find(name);
    return it == metrics.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
  };
  CaseOutput out;
  out.results = {id, c, plan.repeat(id), plan.seed(id)};
  for (const std::string& value : s.combinations[c]) out.results.emplace_back(value);
  for (const std::string& name : s.metrics) out.results.emplace_back(metric(name));
  out.timings = {id, wall_time_s};
  for (const std::string& name : s.timing_metrics) out.timings.emplace_back(metric(name));
  return out;
}

// What a case holds while it runs: its scenario (with the case's overrides), its run and when it
// started. Freed when the case is done.
struct CaseSlot {
  std::optional<Scenario> scenario;
  RunTrace run;
  RunMetrics run_metrics;
  Clock::time_point start;
};

// Runs the cases `todo` through the one scheduler (bench/engine/scheduler.hpp) on `jobs`
// threads: each case is a job that loads its scenario, teaches its mode and plays it back once.
// `done` gets each finished case's rows, from a worker thread.
void RunCases(const SweepPlan& plan, const std::vector<std::size_t>& todo, int jobs,
              const std::function<void(std::size_t id, const CaseOutput& output)>& done) {
  const SweepSpec& s = plan.spec;
  std::vector<CaseSlot> slots(todo.size());
  std::vector<EpisodeJob> episodes(todo.size());
  for (std::size_t i = 0; i < todo.size(); ++i) {
    const std::size_t id = todo[i];
    const std::size_t c = plan.combination(id);
    EpisodeJob& job = episodes[i];
    job.name = "case " + std::to_string(id) + " (" + s.DescribeCombination(c) + ", repeat " +
               std::to_string(plan.repeat(id)) + ", seed " + std::to_string(plan.seed(id)) + ")";
    job.load = [&plan, &slot = slots[i], id]() -> const Scenario* {
      slot.start = Clock::now();
      return &slot.scenario.emplace(LoadScenario(plan.spec.scenario, plan.CaseOverrides(id)));
    };
    job.modes = {s.CombinationMode(c)};
    job.repeats = 1;
  }
  EpisodeCallbacks callbacks;
  callbacks.run_done = [&](std::size_t i, std::size_t, const ModeTeach& teach, RunTrace&& run) {
    CaseSlot& slot = slots[i];
    slot.run_metrics = ComputeRunMetrics(teach.trace, run, slot.scenario->config.metrics);
    slot.run = std::move(run);
  };
  callbacks.mode_done = [&](std::size_t i, std::size_t, ModeTeach&& teach) {
    CaseSlot& slot = slots[i];
    const AggregateMetrics aggregate =
        AggregateMode(*slot.scenario, teach, {slot.run}, {slot.run_metrics});
    done(todo[i], CaseRows(plan, todo[i], FlatMetrics(aggregate), SecondsSince(slot.start)));
    slot = CaseSlot{};
  };
  RunEpisodes(std::move(episodes), jobs, nullptr, callbacks);
}

// sweep.json at the start: the plan, the command and how many cases the folder holds already.
nlohmann::json StartRecord(const SweepPlan& plan, const SweepShard& shard,
                           const std::string& command_line, const FolderState& state,
                           const std::filesystem::path& out) {
  nlohmann::json record = SweepJson(plan, shard);
  record["command"] = command_line;
  record["git_revision"] = RETRACE_GIT_REVISION;
  record["build_type"] = RETRACE_BUILD_TYPE;
  record["cases_done"] = state.results.rows.size();
  io::WriteJsonAtomic(out / "sweep.json", record);
  for (const std::string& warning : plan.warnings)
    std::cerr << "retrace: warning: " << warning << "\n";
  if (!state.results.dropped.empty()) {
    std::cerr
        << "retrace: warning: " << (out / "results.csv").string()
        << ": dropped a half-written last row (the sweep was interrupted); its case runs again\n";
  }
  return record;
}

// The shard's cases that results.csv does not hold yet, in case order.
std::vector<std::size_t> CasesToRun(const SweepPlan& plan, const SweepShard& shard,
                                    const FolderState& state) {
  std::set<std::size_t> done;
  for (const SweepRow& row : state.results.rows) done.insert(row.case_id);
  std::vector<std::size_t> todo;
  for (std::size_t id = 0; id < plan.spec.case_count(); ++id) {
    if (shard.Contains(id) && !done.contains(id)) todo.push_back(id);
  }
  return todo;
}

// Runs the cases `todo`, appending each one's rows as soon as it is done, with a countdown.
void RunAndAppend(const SweepPlan& plan, const std::vector<std::size_t>& todo, int jobs,
                  const std::filesystem::path& out, const FolderState& state,
                  std::size_t shard_cases) {
  const SweepSpec& spec = plan.spec;
  std::set<std::size_t> timed;
  for (const SweepRow& row : state.timings.rows) timed.insert(row.case_id);
  SweepTableAppender results(out / "results.csv", ResultsSchema(spec.parameters, spec.metrics),
                             state.results.complete_size);
  SweepTableAppender timings(out / "timings.csv", TimingsSchema(spec.timing_metrics),
                             state.timings.complete_size);
  ProgressLine progress;
  progress.CountdownPhase("sweep " + spec.name, static_cast<int>(shard_cases),
                          static_cast<int>(shard_cases - todo.size()));
  try {
    RunCases(plan, todo, jobs, [&](std::size_t id, const CaseOutput& output) {
      // results.csv first: a case counts as done once its row is there; its timing row is
      // informative only.
      results.Append(output.results);
      if (!timed.contains(id)) timings.Append(output.timings);
      progress.UnitDone();
    });
  } catch (...) {
    progress.Clear();
    throw;
  }
  progress.Clear();
}

// Every case of the shard is done: the tables rewritten sorted by case id; returns the results.
SweepTable PublishTables(const SweepSpec& spec, const std::filesystem::path& out,
                         std::size_t shard_cases) {
  const SweepTableSchema results_schema = ResultsSchema(spec.parameters, spec.metrics);
  const SweepTableSchema timings_schema = TimingsSchema(spec.timing_metrics);
  SweepTable final_results =
      ReadSweepTable(out / "results.csv", results_schema, PartialRow::kReject);
  RETRACE_CHECK(final_results.rows.size() == shard_cases);
  WriteSortedSweepTable(out / "results.csv", results_schema, final_results.rows);
  WriteSortedSweepTable(
      out / "timings.csv", timings_schema,
      ReadSweepTable(out / "timings.csv", timings_schema, PartialRow::kDrop).rows);
  return final_results;
}

// What the sweep did, and its summary table (or how to join the shards).
void PrintSweepSummary(const SweepSpec& spec, const SweepShard& shard, std::size_t shard_cases,
                       std::size_t cases_run, double wall_time, const std::filesystem::path& out,
                       const SweepTable& final_results) {
  std::cout << "sweep " << spec.name << " (" << spec.scenario.string()
            << "): " << spec.combinations.size() << " combinations x " << spec.repeats
            << " repeats = " << spec.case_count() << " cases\n";
  if (shard.count > 1) std::cout << "shard " << shard.ToString() << ": ";
  std::cout << shard_cases << (shard_cases == 1 ? " case" : " cases") << " done (" << cases_run
            << " now, " << shard_cases - cases_run << " before) in " << FormatDuration(wall_time)
            << "; results in " << (out / "results.csv").string() << "\n";
  if (shard.count == 1) {
    std::cout << SweepSummaryTable(ResultsSchema(spec.parameters, spec.metrics),
                                   spec.parameters.size(), final_results.rows);
  } else {
    std::cout << "join the " << shard.count
              << " shards with `retrace merge <their folders> --out <folder>`\n";
  }
}

}  // namespace

void AddSweepOptions(CLI::App* command, SweepOptions* options) {
  command->add_option("file", options->file, "Sweep file (YAML, see sweeps/)")->required();
  AddJobsOption(command, &options->jobs, "Cases run at once, one thread each");
  AddOutOption(command, &options->out,
               "Results folder (default: results/sweeps/<name>, or .../<name>/shard-<i>-of-<N>)");
  command->add_option("--shard", options->shard,
                      "Run only shard i of N: the cases with case % N == i - 1");
  AddSetOption(command, &options->overrides, "a scenario key in every case: a.b.c=value");
  command->add_flag("!--no-plot", options->plot, "Do not render sweep.png");
  AddNoReportFlag(command, &options->report,
                  "Do not write report.html, the sweep's page of its plot and results table "
                  "(retrace report does it later)");
}

int RunSweepCommand(const SweepOptions& options, const std::string& command_line) {
  const auto wall_start = Clock::now();
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : options.overrides) overrides.push_back(io::ParseOverride(text));
  const SweepShard shard = options.shard.empty() ? SweepShard{} : ParseShard(options.shard);
  const int jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
  const SweepPlan plan = PlanSweep(LoadSweepSpec(options.file, overrides), jobs);
  const SweepSpec& spec = plan.spec;
  const std::filesystem::path out =
      options.out.empty() ? DefaultSweepFolder(spec.name, shard) : options.out;
  // A folder of another sweep is an error before anything is written.
  RequireFolderOrNothing(out);
  InspectFolder(out, plan, shard);

  std::filesystem::create_directories(out);
  const SweepFolderLock lock(out);
  // Again, now that no other process can write the folder.
  const FolderState state = InspectFolder(out, plan, shard);
  nlohmann::json record = StartRecord(plan, shard, command_line, state, out);
  const std::size_t shard_cases = shard.CaseCount(spec.case_count());
  const std::vector<std::size_t> todo = CasesToRun(plan, shard, state);
  RunAndAppend(plan, todo, jobs, out, state, shard_cases);
  const SweepTable final_results = PublishTables(spec, out, shard_cases);
  const double wall_time = SecondsSince(wall_start);
  record["cases_done"] = shard_cases;
  record["complete"] = true;
  record["cases_run"] = todo.size();
  record["wall_time_s"] = wall_time;
  io::WriteJsonAtomic(out / "sweep.json", record);

  // The plot needs every case, so a shard leaves it to `retrace merge`.
  if (options.plot && shard.count == 1) {
    const std::string problem = PlotSweepFolder(out, spec.name, spec.plot_parameters, spec.metrics);
    if (!problem.empty())
      std::cerr << "retrace: warning: no sweep.png: " << problem << " (results.csv is complete)\n";
  }
  PrintSweepSummary(spec, shard, shard_cases, todo.size(), wall_time, out, final_results);
  if (options.report) WriteReportAtEnd(out);
  return 0;
}

}  // namespace retrace::bench
