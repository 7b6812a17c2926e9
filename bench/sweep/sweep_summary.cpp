#include "bench/sweep/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "core/format.hpp"

namespace retrace::bench {
namespace {

constexpr std::size_t kFirstParameter = 4;  // case, combo, repeat, seed

std::string FormatMean(double sum, int count) {
  if (count == 0) return "-";
  return core::Printf("%.4g", sum / count);
}

}  // namespace

std::string SweepSummaryTable(const SweepTableSchema& schema, std::size_t parameter_count,
                              const std::vector<SweepRow>& rows, std::size_t max_combinations) {
  const std::size_t first_metric = kFirstParameter + parameter_count;
  // Rows by combination, in combo order.
  std::map<std::size_t, std::vector<const SweepRow*>> by_combo;
  for (const SweepRow& row : rows)
    by_combo[std::strtoull(row.fields[1].c_str(), nullptr, 10)].push_back(&row);

  std::vector<std::vector<std::string>> table;
  std::vector<std::string> header = {"combo"};
  for (std::size_t i = kFirstParameter; i < schema.header.size(); ++i)
    header.push_back(schema.header[i]);
  header.insert(header.begin() + 1 + static_cast<std::ptrdiff_t>(parameter_count), "runs");
  table.push_back(header);
  for (const auto& [combo, members] : by_combo) {
    if (table.size() > max_combinations) break;
    std::vector<std::string> line = {std::to_string(combo)};
    for (std::size_t p = kFirstParameter; p < first_metric; ++p)
      line.push_back(members.front()->fields[p]);
    line.push_back(std::to_string(members.size()));
    for (std::size_t m = first_metric; m < schema.header.size(); ++m) {
      double sum = 0.0;
      int count = 0;
      for (const SweepRow* row : members) {
        const double v = std::strtod(row->fields[m].c_str(), nullptr);
        if (std::isfinite(v)) sum += v, ++count;
      }
      line.push_back(FormatMean(sum, count));
    }
    table.push_back(line);
  }

  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : table) {
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  }
  std::string out;
  for (const auto& line : table) {
    std::string text;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (i > 0) text += "  ";
      text += line[i] + std::string(width[i] - line[i].size(), ' ');
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out += text + "\n";
  }
  if (by_combo.size() > max_combinations) {
    out += "... " + std::to_string(by_combo.size() - max_combinations) +
           " more combinations in results.csv\n";
  }
  return out;
}

}  // namespace retrace::bench
