// sweep.png from results.csv: the rows read strictly (a wrong file must not become a wrong
// figure), grouped by parameter combination and handed to the renderer as plain data.

#include "bench/sweep/sweep_plot.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

#include "core/errors.hpp"
#include "io/csv_reader.hpp"
#include "viz/sweep_figure.hpp"

namespace retrace::bench {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw core::IoError(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string Quoted(const std::string& s) {
  constexpr std::size_t kMax = 40;
  return "'" + (s.size() > kMax ? s.substr(0, kMax) + "..." : s) + "'";
}

// The index of every name in `header`; IoError naming the first that is missing.
std::vector<std::size_t> Columns(const std::vector<std::string>& header,
                                 const std::vector<std::string>& names, const char* kind,
                                 const std::filesystem::path& file) {
  std::vector<std::size_t> out;
  for (const std::string& n : names) {
    const auto it = std::find(header.begin(), header.end(), n);
    if (it == header.end()) {
      throw core::IoError(file.string() + ":1: no column " + Quoted(n) + " for the " + kind +
                          " of that name");
    }
    out.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  return out;
}

// The header must start with case,combo,repeat,seed and name no column twice.
void CheckHeader(const io::CsvRecord& header_record, const std::filesystem::path& file) {
  const std::vector<std::string>& header = header_record.cells;
  const std::vector<std::string> fixed = {"case", "combo", "repeat", "seed"};
  if (header.size() < fixed.size() || !std::equal(fixed.begin(), fixed.end(), header.begin())) {
    Fail(file, header_record.line,
         "the header must start with case,combo,repeat,seed (a sweep's results.csv)");
  }
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (std::find(header.begin(), header.begin() + static_cast<std::ptrdiff_t>(i), header[i]) !=
        header.begin() + static_cast<std::ptrdiff_t>(i)) {
      Fail(file, header_record.line,
           "column " + Quoted(header[i]) + " appears twice in the header");
    }
  }
}

// Groups the cases by combo: each combo's parameter values (the same in every repeat) and its
// metrics per repeat.
class CaseGrouper {
 public:
  CaseGrouper(const std::filesystem::path& file, std::size_t cells,
              std::vector<std::size_t> param_cols, std::vector<std::size_t> metric_cols,
              viz::SweepFigureData* data)
      : file_(file),
        cells_(cells),
        param_cols_(std::move(param_cols)),
        metric_cols_(std::move(metric_cols)),
        data_(*data) {}

  void Add(const io::CsvRecord& rec) {
    if (rec.cells.size() != cells_) {
      Fail(file_, rec.line,
           "expected " + std::to_string(cells_) + " cells as in the header, got " +
               std::to_string(rec.cells.size()));
    }
    const std::string& combo = rec.cells[1];
    const std::string& repeat = rec.cells[2];
    if (combo.empty()) Fail(file_, rec.line, "empty combo cell");
    const auto [where, fresh] = seen_.emplace(std::make_pair(combo, repeat), rec.line);
    if (!fresh) {
      Fail(file_, rec.line,
           "combo " + Quoted(combo) + " repeat " + Quoted(repeat) +
               " appears twice (also at line " + std::to_string(where->second) + ")");
    }
    viz::SweepCombination& c = Combination(combo, ParameterValues(rec), rec.line);
    for (std::size_t k = 0; k < metric_cols_.size(); ++k) {
      const std::string& cell = rec.cells[metric_cols_[k]];
      const std::optional<double> v = io::ParseCsvNumber(cell);
      if (!v) {
        Fail(file_, rec.line,
             data_.metrics[k] + ": expected a number or nan, got " + Quoted(cell));
      }
      c.metrics[k].push_back(*v);
    }
  }

 private:
  std::vector<std::string> ParameterValues(const io::CsvRecord& rec) const {
    std::vector<std::string> values;
    for (std::size_t k = 0; k < param_cols_.size(); ++k) {
      const std::string& v = rec.cells[param_cols_[k]];
      if (v.empty()) Fail(file_, rec.line, data_.parameters[k] + ": empty value");
      values.push_back(v);
    }
    return values;
  }

  // The combination of `combo`, added when first seen; its values must agree with `values`.
  viz::SweepCombination& Combination(const std::string& combo,
                                     const std::vector<std::string>& values, int line) {
    const auto [it, added] = combo_index_.emplace(combo, data_.combinations.size());
    if (added) {
      combo_line_[combo] = line;
      viz::SweepCombination c;
      c.values = values;
      c.metrics.resize(data_.metrics.size());
      data_.combinations.push_back(std::move(c));
    }
    viz::SweepCombination& c = data_.combinations[it->second];
    for (std::size_t k = 0; k < values.size(); ++k) {
      if (values[k] != c.values[k]) {
        Fail(file_, line,
             "combo " + Quoted(combo) + " has " + data_.parameters[k] + " = " +
                 Quoted(values[k]) + " here but " + Quoted(c.values[k]) + " at line " +
                 std::to_string(combo_line_[combo]));
      }
    }
    return c;
  }

  const std::filesystem::path& file_;
  std::size_t cells_;
  std::vector<std::size_t> param_cols_;
  std::vector<std::size_t> metric_cols_;
  viz::SweepFigureData& data_;
  std::map<std::string, std::size_t> combo_index_;           // combo cell -> combination
  std::map<std::string, int> combo_line_;                    // where each combo was first seen
  std::map<std::pair<std::string, std::string>, int> seen_;  // (combo, repeat) -> line
};

}  // namespace

viz::SweepFigureData ReadSweepResults(const std::filesystem::path& file,
                                      const std::vector<std::string>& parameters,
                                      const std::vector<std::string>& metrics) {
  const std::vector<io::CsvRecord> records = io::ReadCsvFile(file);
  if (records.empty())
    throw core::IoError(file.string() + ": empty file, expected a sweep's results.csv");
  CheckHeader(records.front(), file);
  const std::vector<std::string>& header = records.front().cells;
  viz::SweepFigureData data;
  data.parameters = parameters;
  data.metrics = metrics;
  std::vector<std::size_t> param_cols = Columns(header, parameters, "varied parameter", file);
  std::vector<std::size_t> metric_cols = Columns(header, metrics, "metric", file);
  CaseGrouper cases(file, header.size(), std::move(param_cols), std::move(metric_cols), &data);
  for (std::size_t r = 1; r < records.size(); ++r) cases.Add(records[r]);
  if (data.combinations.empty())
    throw core::IoError(file.string() + ": holds a header but no case");
  return data;
}

void RenderSweepPlot(const std::filesystem::path& results_csv,
                     const std::vector<std::string>& parameters,
                     const std::vector<std::string>& metrics, const std::filesystem::path& png,
                     const std::string& title) {
  const viz::SweepFigureData data = ReadSweepResults(results_csv, parameters, metrics);
  viz::FigureOptions options;
  // About 560 px per parameter column keeps tick labels apart; never narrower than the other
  // figures' usual 1200 px.
  options.width = std::clamp(560 * static_cast<int>(parameters.size()), 1200, 8000);
  options.supersample = 1;
  options.title = title;
  viz::RenderSweepFigure(data, png, options);
}

}  // namespace retrace::bench
