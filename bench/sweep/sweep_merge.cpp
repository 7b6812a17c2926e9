#include "bench/sweep/sweep_merge.hpp"

#include <chrono>
#include <map>
#include <sstream>

#include "bench/metrics/provenance.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/sweep/sweep_folder.hpp"
#include "bench/sweep/sweep_summary.hpp"
#include "core/errors.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

[[noreturn]] void Fail(const std::string& message) { throw core::ConfigError("", message, true); }

std::string Name(const std::filesystem::path& folder) { return folder.string(); }

using Folders = std::vector<std::filesystem::path>;

// The sweep.json of every shard folder.
std::vector<SweepRecord> ReadShardRecords(const Folders& inputs) {
  std::vector<SweepRecord> records;
  for (const std::filesystem::path& folder : inputs) {
    if (!std::filesystem::is_directory(folder))
      throw core::IoError(Name(folder) + ": no such folder");
    if (!std::filesystem::exists(folder / "sweep.json")) {
      throw core::IoError(Name(folder) + ": not a sweep results folder (it has no sweep.json)");
    }
    records.push_back(ReadSweepRecord(folder / "sweep.json"));
  }
  return records;
}

// Which sweep and shard each folder holds: one sweep, every shard exactly once.
void RequireEveryShardOnce(const Folders& inputs, const std::vector<SweepRecord>& records) {
  const SweepRecord& first = records.front();
  const int count = first.shard.count;
  std::vector<int> owner(static_cast<std::size_t>(count) + 1, -1);
  for (std::size_t i = 0; i < records.size(); ++i) {
    const SweepRecord& r = records[i];
    if (r.identity != first.identity) {
      Fail(Name(inputs[i]) + " holds another sweep than " + Name(inputs[0]) + " ('" + r.name +
           "' " + r.identity + " vs '" + first.name + "' " + first.identity + ")");
    }
    if (r.shard.count != count) {
      Fail(Name(inputs[i]) + " is shard " + r.shard.ToString() + " but " + Name(inputs[0]) +
           " is shard " + first.shard.ToString() +
           ": the shards of one merge must split the sweep the same way");
    }
    int& slot = owner[static_cast<std::size_t>(r.shard.index)];
    if (slot >= 0) {
      Fail("shard " + r.shard.ToString() + " is given twice: " +
           Name(inputs[static_cast<std::size_t>(slot)]) + " and " + Name(inputs[i]));
    }
    slot = static_cast<int>(i);
  }
  std::string missing;
  for (int index = 1; index <= count; ++index) {
    if (owner[static_cast<std::size_t>(index)] < 0) {
      missing +=
          (missing.empty() ? "" : ", ") + std::to_string(index) + "/" + std::to_string(count);
    }
  }
  if (!missing.empty())
    Fail("missing shard " + missing + " of sweep '" + first.name +
         "': give the folder of every shard");
}

// The output must not be a shard (merging would overwrite it) nor another sweep's folder.
void RequireMergeOutputFree(const Folders& inputs, const std::filesystem::path& out,
                            const SweepRecord& first) {
  for (const std::filesystem::path& folder : inputs) {
    std::error_code ec;
    if (std::filesystem::equivalent(folder, out, ec)) {
      Fail("--out " + Name(out) + " is one of the shard folders; choose another");
    }
  }
  if (std::filesystem::exists(out / "sweep.json")) {
    const SweepRecord existing = ReadSweepRecord(out / "sweep.json");
    if (existing.identity != first.identity || existing.shard.count != 1) {
      Fail(Name(out) + " holds results of another sweep ('" + existing.name + "' " +
           existing.identity + ", shard " + existing.shard.ToString() +
           "); use another --out or remove it");
    }
  }
}

// A shard's results.csv, which must hold every case of the shard.
SweepTable ReadCompleteShardResults(const std::filesystem::path& folder, const SweepRecord& record,
                                    std::size_t sweep_cases, const SweepTableSchema& schema) {
  const SweepShard& shard = record.shard;
  const SweepTable table = ReadSweepTable(folder / "results.csv", schema, PartialRow::kReject);
  const std::size_t expected = shard.CaseCount(sweep_cases);
  if (!record.complete || table.rows.size() != expected) {
    Fail(Name(folder) + ": shard " + shard.ToString() +
         " is incomplete: " + std::to_string(table.rows.size()) + " of " +
         std::to_string(expected) + " cases done; run its `retrace sweep ... --shard " +
         shard.ToString() + "` again to finish it");
  }
  return table;
}

// The shards' tables joined, in the order read (written sorted by case).
struct MergedTables {
  SweepTableSchema schema;
  SweepTableSchema timings_schema;
  std::vector<SweepRow> rows;
  std::vector<SweepRow> timings;
};

// Every shard's rows: every shard complete, every case exactly once; the timings of each shard's
// own cases.
MergedTables JoinShardTables(const Folders& inputs, const std::vector<SweepRecord>& records) {
  const SweepRecord& first = records.front();
  MergedTables joined{
      ResultsSchema(first.parameters, first.metrics), TimingsSchema(first.timing_metrics), {}, {}};
  std::map<std::size_t, std::size_t> case_owner;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const SweepShard& shard = records[i].shard;
    const std::filesystem::path file = inputs[i] / "results.csv";
    const SweepTable table =
        ReadCompleteShardResults(inputs[i], records[i], first.cases, joined.schema);
    for (const SweepRow& row : table.rows) {
      const std::string where = file.string() + ":" + std::to_string(row.line_number) + ": case " +
                                std::to_string(row.case_id);
      if (row.case_id >= first.cases)
        Fail(where + ": the sweep has only " + std::to_string(first.cases) + " cases");
      if (!shard.Contains(row.case_id)) Fail(where + ": not a case of shard " + shard.ToString());
      const auto [it, inserted] = case_owner.emplace(row.case_id, i);
      if (!inserted)
        Fail("case " + std::to_string(row.case_id) + " is in both " + Name(inputs[it->second]) +
             " and " + Name(inputs[i]));
      joined.rows.push_back(row);
    }
    for (SweepRow& row :
         ReadSweepTable(inputs[i] / "timings.csv", joined.timings_schema, PartialRow::kDrop).rows) {
      if (shard.Contains(row.case_id) && row.case_id < first.cases)
        joined.timings.push_back(std::move(row));
    }
  }
  for (std::size_t id = 0; id < first.cases; ++id) {
    if (!case_owner.contains(id))
      Fail("case " + std::to_string(id) + " is missing from every shard");
  }
  return joined;
}

// sweep.json of the joined folder: the first shard's, now for the whole sweep, complete, with the
// shards it was merged from.
nlohmann::json MergedSweepJson(const SweepRecord& first, const Folders& inputs) {
  nlohmann::json record = first.json;
  record["shard"] = SweepShard{}.ToString();
  record["shard_cases"] = first.cases;
  record["cases_done"] = first.cases;
  record["complete"] = true;
  record["cases_run"] = 0;
  record["merged_from"] = nlohmann::json::array();
  for (const std::filesystem::path& folder : inputs)
    record["merged_from"].push_back(folder.string());
  return record;
}

// sweep.png of the joined folder; a failure is a warning (the tables are complete).
void PlotMergedSweep(const std::filesystem::path& out, const SweepRecord& first,
                     ProgressSink* progress) {
  const std::string problem =
      PlotSweepFolder(out, first.name, first.plot_parameters, first.metrics);
  if (!problem.empty()) Warn(progress, "no sweep.png: " + problem + " (results.csv is complete)");
}

// The shards checked and joined before anything is written.
MergedTables CheckAndJoin(const MergeRequest& request, const std::vector<SweepRecord>& records) {
  RequireEveryShardOnce(request.inputs, records);
  RequireMergeOutputFree(request.inputs, request.out, records.front());
  return JoinShardTables(request.inputs, records);
}

}  // namespace

SweepMerge MergeSweepShards(const MergeRequest& request, const std::string& command_line,
                            ProgressSink* progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  const Folders& inputs = request.inputs;
  if (inputs.empty()) Fail("merge: name the results folders of the shards");
  const std::vector<SweepRecord> records = ReadShardRecords(inputs);
  const SweepRecord& first = records.front();
  const MergedTables joined = CheckAndJoin(request, records);

  RequireFolderOrNothing(request.out);
  std::filesystem::create_directories(request.out);
  const SweepFolderLock lock(request.out);
  WriteSortedSweepTable(request.out / "results.csv", joined.schema, joined.rows);
  WriteSortedSweepTable(request.out / "timings.csv", joined.timings_schema, joined.timings);
  nlohmann::json record = MergedSweepJson(first, inputs);
  SweepMerge merged{request.out, first.name,    first.shard.count,       first.cases,
                    0.0,         joined.schema, first.parameters.size(), joined.rows};
  merged.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  // The build's revision and type stay the shards' (they ran the cases).
  Provenance provenance;
  provenance.command_line = command_line;
  provenance.wall_time_s = merged.wall_time_s;
  WriteProvenance(provenance, &record);
  io::WriteJsonAtomic(request.out / "sweep.json", record);
  if (request.plot) PlotMergedSweep(request.out, first, progress);
  return merged;
}

std::string SweepMergeSummary(const SweepMerge& merged) {
  std::ostringstream text;
  text << "merged " << merged.shards << " shards of sweep " << merged.name << ": " << merged.cases
       << " cases in " << FormatDuration(merged.wall_time_s) << "; results in "
       << (merged.out / "results.csv").string() << "\n";
  text << SweepSummaryTable(merged.schema, merged.parameter_count, merged.rows);
  return text.str();
}

}  // namespace retrace::bench
