// sweep.png from results.csv: the rows read strictly (a wrong file must not become a wrong
// figure), grouped by parameter combination and handed to the renderer as plain data.

#include "bench/sweep_plot.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "core/errors.hpp"
#include "viz/sweep_figure.hpp"

namespace retrace::bench {
namespace {

struct CsvRecord {
  int line = 0;  // 1-based line where the record starts
  std::vector<std::string> cells;
};

[[noreturn]] void Fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw core::IoError(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string Quoted(const std::string& s) {
  constexpr std::size_t kMax = 40;
  return "'" + (s.size() > kMax ? s.substr(0, kMax) + "..." : s) + "'";
}

// RFC 4180: cells separated by commas, records by LF or CRLF; a cell in double quotes may hold
// commas, line breaks and doubled quotes. Blank lines are skipped.
std::vector<CsvRecord> ParseCsv(const std::string& text, const std::filesystem::path& file) {
  std::vector<CsvRecord> records;
  CsvRecord record;
  std::string cell;
  int line = 1;
  record.line = 1;
  bool quoted = false;      // inside a quoted cell
  bool was_quoted = false;  // the current cell was quoted and has closed
  bool any = false;         // the record has content (a blank line has none)
  auto end_cell = [&] {
    record.cells.push_back(std::move(cell));
    cell.clear();
    was_quoted = false;
  };
  auto end_record = [&] {
    if (any) {
      end_cell();
      records.push_back(std::move(record));
    }
    record = CsvRecord{};
    cell.clear();
    was_quoted = false;
    any = false;
    record.line = line;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          cell += '"';
          ++i;
        } else {
          quoted = false;
          was_quoted = true;
        }
      } else {
        if (c == '\n') ++line;
        cell += c;
      }
      continue;
    }
    if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
    if (c == '\n') {
      ++line;
      end_record();
      continue;
    }
    any = true;
    if (c == ',') {
      end_cell();
    } else if (c == '"') {
      if (was_quoted || !cell.empty())
        Fail(file, line, "a double quote inside a cell that is not quoted");
      quoted = true;
    } else if (was_quoted) {
      Fail(file, line, "text after the closing quote of a cell");
    } else {
      cell += c;
    }
  }
  if (quoted) Fail(file, record.line, "a quoted cell is not closed before the end of the file");
  end_record();
  return records;
}

std::string ReadAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw core::IoError(file.string() + ": cannot open the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw core::IoError(file.string() + ": cannot read the file");
  return ss.str();
}

// A metric cell: a number, or nan/inf as io::FormatCsvNumber writes them (any case).
bool ParseMetric(const std::string& text, double* value) {
  const std::size_t b = text.find_first_not_of(" \t");
  const std::size_t e = text.find_last_not_of(" \t");
  if (b == std::string::npos) return false;
  std::size_t start = b;
  if (text[start] == '+') ++start;  // from_chars takes no '+'
  if (start > e) return false;
  const char* first = text.data() + start;
  const char* last = text.data() + e + 1;
  const auto [ptr, ec] = std::from_chars(first, last, *value);
  return ec == std::errc() && ptr == last;
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

viz::SweepFigureData ReadSweep(const std::filesystem::path& file,
                               const std::vector<std::string>& parameters,
                               const std::vector<std::string>& metrics) {
  const std::vector<CsvRecord> records = ParseCsv(ReadAll(file), file);
  if (records.empty())
    throw core::IoError(file.string() + ": empty file, expected a sweep's results.csv");
  const std::vector<std::string>& header = records.front().cells;
  const std::vector<std::string> fixed = {"case", "combo", "repeat", "seed"};
  if (header.size() < fixed.size() || !std::equal(fixed.begin(), fixed.end(), header.begin())) {
    Fail(file, records.front().line,
         "the header must start with case,combo,repeat,seed (a sweep's results.csv)");
  }
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (std::find(header.begin(), header.begin() + static_cast<std::ptrdiff_t>(i), header[i]) !=
        header.begin() + static_cast<std::ptrdiff_t>(i)) {
      Fail(file, records.front().line,
           "column " + Quoted(header[i]) + " appears twice in the header");
    }
  }
  const std::vector<std::size_t> param_cols = Columns(header, parameters, "varied parameter", file);
  const std::vector<std::size_t> metric_cols = Columns(header, metrics, "metric", file);

  viz::SweepFigureData data;
  data.parameters = parameters;
  data.metrics = metrics;
  std::map<std::string, std::size_t> combo_index;           // combo cell -> combination
  std::map<std::string, int> combo_line;                    // where each combo was first seen
  std::map<std::pair<std::string, std::string>, int> seen;  // (combo, repeat) -> line
  for (std::size_t r = 1; r < records.size(); ++r) {
    const CsvRecord& rec = records[r];
    if (rec.cells.size() != header.size()) {
      Fail(file, rec.line,
           "expected " + std::to_string(header.size()) + " cells as in the header, got " +
               std::to_string(rec.cells.size()));
    }
    const std::string& combo = rec.cells[1];
    const std::string& repeat = rec.cells[2];
    if (combo.empty()) Fail(file, rec.line, "empty combo cell");
    const auto [where, fresh] = seen.emplace(std::make_pair(combo, repeat), rec.line);
    if (!fresh) {
      Fail(file, rec.line,
           "combo " + Quoted(combo) + " repeat " + Quoted(repeat) +
               " appears twice (also at line " + std::to_string(where->second) + ")");
    }
    std::vector<std::string> values;
    for (std::size_t k = 0; k < param_cols.size(); ++k) {
      const std::string& v = rec.cells[param_cols[k]];
      if (v.empty()) Fail(file, rec.line, parameters[k] + ": empty value");
      values.push_back(v);
    }
    auto [it, added] = combo_index.emplace(combo, data.combinations.size());
    if (added) {
      combo_line[combo] = rec.line;
      viz::SweepCombination c;
      c.values = values;
      c.metrics.resize(metrics.size());
      data.combinations.push_back(std::move(c));
    }
    viz::SweepCombination& c = data.combinations[it->second];
    for (std::size_t k = 0; k < values.size(); ++k) {
      if (values[k] != c.values[k]) {
        Fail(file, rec.line,
             "combo " + Quoted(combo) + " has " + parameters[k] + " = " + Quoted(values[k]) +
                 " here but " + Quoted(c.values[k]) + " at line " +
                 std::to_string(combo_line[combo]));
      }
    }
    for (std::size_t k = 0; k < metric_cols.size(); ++k) {
      double v = 0.0;
      const std::string& cell = rec.cells[metric_cols[k]];
      if (!ParseMetric(cell, &v))
        Fail(file, rec.line, metrics[k] + ": expected a number or nan, got " + Quoted(cell));
      c.metrics[k].push_back(v);
    }
  }
  if (data.combinations.empty())
    throw core::IoError(file.string() + ": holds a header but no case");
  return data;
}

}  // namespace

void RenderSweepPlot(const std::filesystem::path& results_csv,
                     const std::vector<std::string>& parameters,
                     const std::vector<std::string>& metrics, const std::filesystem::path& png,
                     const std::string& title) {
  const viz::SweepFigureData data = ReadSweep(results_csv, parameters, metrics);
  viz::FigureOptions options;
  // About 560 px per parameter column keeps tick labels apart; never narrower than the other
  // figures' usual 1200 px.
  options.width = std::clamp(560 * static_cast<int>(parameters.size()), 1200, 8000);
  options.supersample = 1;
  options.title = title;
  viz::RenderSweepFigure(data, png, options);
}

}  // namespace retrace::bench
