#include "bench/calibration/log_comparison.hpp"

#include <cmath>
#include <cstdio>
#include <map>

#include "core/errors.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_reader.hpp"
#include "io/json_writer.hpp"
#include "viz/figures.hpp"

namespace retrace::bench {

namespace {

// The columns of errors.csv this reads, by name.
std::vector<double> Column(const std::vector<io::CsvRecord>& records, const std::string& name,
                           const std::filesystem::path& file) {
  if (records.empty()) throw core::IoError(file.string() + ": empty file, no header");
  const std::vector<std::string>& header = records.front().cells;
  std::size_t column = header.size();
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) column = i;
  }
  if (column == header.size())
    throw core::IoError(file.string() + ": no column '" + name + "' (not log-localize's)");
  std::vector<double> values;
  for (std::size_t r = 1; r < records.size(); ++r) {
    const std::vector<std::string>& cells = records[r].cells;
    const std::optional<double> v =
        column < cells.size() ? io::ParseCsvNumber(cells[column]) : std::nullopt;
    if (!v) {
      throw core::IoError(file.string() + ":" + std::to_string(records[r].line) + ": '" + name +
                          "' is not a number");
    }
    values.push_back(*v);
  }
  return values;
}

double Number(const nlohmann::json& j, const char* key, const char* sub = nullptr) {
  const nlohmann::json* v = j.contains(key) ? &j.at(key) : nullptr;
  if (v != nullptr && sub != nullptr) v = v->contains(sub) ? &v->at(sub) : nullptr;
  return v != nullptr && v->is_number() ? v->get<double>() : std::nan("");
}

std::string Cell(double v, const char* format) {
  if (!std::isfinite(v)) return "–";
  return core::Printf(format, v);
}

}  // namespace

std::vector<LoggedRun> ReadLoggedRuns(const std::vector<std::filesystem::path>& dirs,
                                      const std::vector<std::string>& labels) {
  if (!labels.empty() && labels.size() != dirs.size()) {
    throw core::ConfigError("--labels", "gives " + std::to_string(labels.size()) + " labels for " +
                                            std::to_string(dirs.size()) + " folders");
  }
  std::vector<LoggedRun> runs;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    LoggedRun run;
    std::filesystem::path name = dirs[i].lexically_normal();
    if (name.filename().empty()) name = name.parent_path();
    run.label = labels.empty() ? name.filename().string() : labels[i];
    run.metrics = io::ReadJsonFile(dirs[i] / "metrics.json");
    if (!run.metrics.is_object() || !run.metrics.contains("localization_error_on_route_m")) {
      throw core::IoError((dirs[i] / "metrics.json").string() +
                          ": not the metrics of retrace log-localize");
    }
    const std::filesystem::path errors = dirs[i] / "errors.csv";
    const std::vector<io::CsvRecord> records = io::ReadCsvFile(errors);
    run.driven_m = Column(records, "driven_m", errors);
    run.path_distance_m = Column(records, "path_distance_m", errors);
    run.localization_error_m = Column(records, "localization_error_m", errors);
    runs.push_back(std::move(run));
  }
  return runs;
}

std::string LoggedRunsTable(const std::vector<LoggedRun>& runs) {
  std::string t =
      "| run | scans | localization RMS on the route (m) | p95 on the route (m) | on the route | "
      "RMS overall (m) | lost | beams rejected | update (ms) | real time |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const LoggedRun& r : runs) {
    const nlohmann::json& m = r.metrics;
    t += "| " + r.label + " | " + Cell(Number(m, "scans"), "%.0f") + " | " +
         Cell(Number(m, "localization_error_on_route_m", "rms"), "%.3f") + " | " +
         Cell(Number(m, "localization_error_on_route_m", "p95"), "%.3f") + " | " +
         Cell(100.0 * Number(m, "on_route_fraction"), "%.1f %%") + " | " +
         Cell(Number(m, "localization_error_m", "rms"), "%.3f") + " | " +
         Cell(100.0 * Number(m, "lost_fraction"), "%.1f %%") + " | " +
         Cell(100.0 * Number(m, "rejected_fraction"), "%.1f %%") + " | " +
         Cell(Number(m, "update_time_ms", "mean"), "%.2f") + " | " +
         Cell(Number(m, "real_time_factor"), "%.0f×") + " |\n";
  }
  return t;
}

void WriteLogComparison(const std::filesystem::path& dir, const std::vector<LoggedRun>& runs) {
  io::WriteFileAtomic(dir / "comparison.md", LoggedRunsTable(runs));
  viz::ErrorsFigureData errors;
  errors.x_label = "distance driven in the log (m)";
  errors.top_title = "The log's drive: distance to the taught path";
  errors.top_y_label = "distance to the taught path (m)";
  for (const LoggedRun& r : runs)
    errors.runs.push_back({r.label, r.driven_m, r.path_distance_m, r.localization_error_m});
  viz::RenderErrorsFigure(errors, dir / "errors.png");
}

}  // namespace retrace::bench
