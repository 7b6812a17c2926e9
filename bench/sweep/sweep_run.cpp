#include "bench/sweep/sweep_run.hpp"

#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "bench/engine/parallel.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/scheduler.hpp"
#include "bench/metrics/experiment.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/metrics/provenance.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/sweep/sweep_folder.hpp"
#include "bench/sweep/sweep_summary.hpp"
#include "core/check.hpp"
#include "core/errors.hpp"
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

// What the cases' episodes report to the sweep's sink: their simulated time and whether to
// stop (ProgressSink::Cancelled), but not the scheduler's phases and units, which would replace
// the sweep's countdown of cases.
class CaseEpisodeProgress : public ProgressSink {
 public:
  explicit CaseEpisodeProgress(ProgressSink* sweep) : sweep_(sweep) {}
  void Phase(const std::string&, int) override {}
  void AddSimTime(double seconds) override { sweep_->AddSimTime(seconds); }
  void UnitDone() override {}
  void Warning(const std::string& text) override { sweep_->Warning(text); }
  bool Cancelled() const override { return sweep_->Cancelled(); }

 private:
  ProgressSink* sweep_;
};

// Runs the cases `todo` through the one scheduler (bench/engine/scheduler.hpp) on `jobs`
// threads: each case is a job that loads its scenario, teaches its mode and plays it back once.
// `done` gets each finished case's rows, from a worker thread. `progress` (may be null) gets the
// episodes' simulated time and can stop them.
void RunCases(const SweepPlan& plan, const std::vector<std::size_t>& todo, int jobs,
              ProgressSink* progress,
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
  std::optional<CaseEpisodeProgress> episode_progress;
  if (progress != nullptr) episode_progress.emplace(progress);
  RunEpisodes(std::move(episodes), jobs, episode_progress ? &*episode_progress : nullptr,
              callbacks);
}

// sweep.json at the start: the plan, the command and how many cases the folder holds already.
nlohmann::json StartRecord(const SweepPlan& plan, const SweepShard& shard,
                           const Provenance& provenance, const FolderState& state,
                           const std::filesystem::path& out, ProgressSink* progress) {
  nlohmann::json record = SweepJson(plan, shard);
  WriteProvenance(provenance, &record);
  record["cases_done"] = state.results.rows.size();
  io::WriteJsonAtomic(out / "sweep.json", record);
  for (const std::string& warning : plan.warnings) Warn(progress, warning);
  if (!state.results.dropped.empty()) {
    Warn(progress, (out / "results.csv").string() +
                       ": dropped a half-written last row (the sweep was interrupted); its case "
                       "runs again");
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

// Runs the cases `todo`, appending each one's rows as soon as it is done, counting down.
void RunAndAppend(const SweepPlan& plan, const std::vector<std::size_t>& todo, int jobs,
                  const std::filesystem::path& out, const FolderState& state,
                  std::size_t shard_cases, ProgressSink* progress) {
  const SweepSpec& spec = plan.spec;
  std::set<std::size_t> timed;
  for (const SweepRow& row : state.timings.rows) timed.insert(row.case_id);
  SweepTableAppender results(out / "results.csv", ResultsSchema(spec.parameters, spec.metrics),
                             state.results.complete_size);
  SweepTableAppender timings(out / "timings.csv", TimingsSchema(spec.timing_metrics),
                             state.timings.complete_size);
  if (progress != nullptr) {
    progress->CountdownPhase("sweep " + spec.name, static_cast<int>(shard_cases),
                             static_cast<int>(shard_cases - todo.size()));
  }
  RunCases(plan, todo, jobs, progress, [&](std::size_t id, const CaseOutput& output) {
    // results.csv first: a case counts as done once its row is there; its timing row is
    // informative only.
    results.Append(output.results);
    if (!timed.contains(id)) timings.Append(output.timings);
    if (progress != nullptr) progress->UnitDone();
  });
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

// The plan of the request's sweep and shard, and its folder, checked before anything is
// written: a folder of another sweep is an error.
struct SweepSetup {
  SweepPlan plan;
  SweepShard shard;
  std::filesystem::path out;
  int jobs = 1;
};

SweepSetup SetUpSweep(const SweepRequest& request) {
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : request.overrides) overrides.push_back(io::ParseOverride(text));
  const SweepShard shard = request.shard.empty() ? SweepShard{} : ParseShard(request.shard);
  const int jobs = request.jobs > 0 ? request.jobs : DefaultJobs();
  SweepSetup setup{PlanSweep(LoadSweepSpec(request.file, overrides), jobs), shard, {}, jobs};
  setup.out = request.out.empty() ? DefaultSweepFolder(setup.plan.spec.name, shard) : request.out;
  RequireFolderOrNothing(setup.out);
  InspectFolder(setup.out, setup.plan, shard);
  return setup;
}

// sweep.png of a complete folder; a failure is a warning (the tables are complete).
void PlotOrWarn(const std::filesystem::path& out, const std::string& name,
                const std::vector<std::string>& parameters, const std::vector<std::string>& metrics,
                ProgressSink* progress) {
  const std::string problem = PlotSweepFolder(out, name, parameters, metrics);
  if (!problem.empty()) Warn(progress, "no sweep.png: " + problem + " (results.csv is complete)");
}

}  // namespace

SweepRun RunSweep(const SweepRequest& request, const std::string& command_line,
                  ProgressSink* progress) {
  const auto wall_start = Clock::now();
  const SweepSetup setup = SetUpSweep(request);
  const SweepPlan& plan = setup.plan;
  const std::filesystem::path& out = setup.out;
  std::filesystem::create_directories(out);
  const SweepFolderLock lock(out);
  // Again, now that no other process can write the folder.
  const FolderState state = InspectFolder(out, plan, setup.shard);
  Provenance provenance;
  provenance.command_line = command_line;
  provenance.git_revision = BuildRevision();
  provenance.build_type = BuildType();
  nlohmann::json record = StartRecord(plan, setup.shard, provenance, state, out, progress);
  SweepRun done{plan.spec, setup.shard, out, setup.shard.CaseCount(plan.spec.case_count()),
                0,         0.0,         {}};
  const std::vector<std::size_t> todo = CasesToRun(plan, setup.shard, state);
  RunAndAppend(plan, todo, setup.jobs, out, state, done.shard_cases, progress);
  done.results = PublishTables(plan.spec, out, done.shard_cases).rows;
  done.cases_run = todo.size();
  done.wall_time_s = SecondsSince(wall_start);
  record["cases_done"] = done.shard_cases;
  record["complete"] = true;
  record["cases_run"] = todo.size();
  provenance.wall_time_s = done.wall_time_s;
  WriteProvenance(provenance, &record);
  io::WriteJsonAtomic(out / "sweep.json", record);
  // The plot needs every case, so a shard leaves it to `retrace merge`.
  const SweepSpec& spec = plan.spec;
  if (request.plot && setup.shard.count == 1)
    PlotOrWarn(out, spec.name, spec.plot_parameters, spec.metrics, progress);
  return done;
}

std::string SweepRunSummary(const SweepRun& run) {
  const SweepSpec& spec = run.spec;
  std::ostringstream text;
  text << "sweep " << spec.name << " (" << spec.scenario.string()
       << "): " << spec.combinations.size() << " combinations x " << spec.repeats
       << " repeats = " << spec.case_count() << " cases\n";
  if (run.shard.count > 1) text << "shard " << run.shard.ToString() << ": ";
  text << run.shard_cases << (run.shard_cases == 1 ? " case" : " cases") << " done ("
       << run.cases_run << " now, " << run.shard_cases - run.cases_run << " before) in "
       << FormatDuration(run.wall_time_s) << "; results in " << (run.out / "results.csv").string()
       << "\n";
  if (run.shard.count == 1) {
    text << SweepSummaryTable(ResultsSchema(spec.parameters, spec.metrics), spec.parameters.size(),
                              run.results);
  } else {
    text << "join the " << run.shard.count
         << " shards with `retrace merge <their folders> --out <folder>`\n";
  }
  return text.str();
}

}  // namespace retrace::bench
