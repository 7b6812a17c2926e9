#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench/metrics/internal/run_series.hpp"
#include "bench/metrics/internal/sample_stats.hpp"
#include "bench/metrics/metrics.hpp"
#include "io/csv_writer.hpp"

namespace retrace::bench {
namespace {

using internal::kInf;
// A progress step bigger than this between consecutive samples is a jump of the match (a
// fallback to another part of the path), not a crossing of the stations in between (m).
constexpr double kMaxCrossingStep = 2.0;

// v rounded to 0.1 mm (dividing by the exact 1e4 keeps 0.1 as the double nearest 0.1).
double RoundTenthMm(double v) { return std::round(v * 1e4) / 1e4; }

}  // namespace

namespace internal {

namespace {

// Run r's lateral offset at each station it crosses, interpolated between the two samples
// around it (the first crossing of a station counts; jumps and non-finite offsets are skipped).
void InterpolateRunOffsets(const RunSeries& run, std::size_t r, double spacing,
                           std::size_t stations, Repeatability& out) {
  const std::vector<double>& s = run.progress_m;
  const std::vector<double>& e = run.lateral_offset_m;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const double s0 = s[i], s1 = s[i + 1];
    if (!(s1 > s0) || s1 - s0 > kMaxCrossingStep || !std::isfinite(e[i]) ||
        !std::isfinite(e[i + 1])) {
      continue;
    }
    const double k_lo = std::max(0.0, std::floor(s0 / spacing));
    const double k_hi = std::min(static_cast<double>(stations - 1), std::floor(s1 / spacing) + 1);
    for (double kd = k_lo; kd <= k_hi; kd += 1.0) {
      const std::size_t k = static_cast<std::size_t>(kd);
      const double st = out.station_s_m[k];
      if (st < s0 || st > s1 || !std::isnan(out.offsets_m[k][r])) continue;
      out.offsets_m[k][r] = e[i] + (st - s0) / (s1 - s0) * (e[i + 1] - e[i]);
    }
  }
}

// Each station's standard deviation and spread of the offsets (two runs or more), the largest
// spread and their mean standard deviation: the repeatability.
void SummarizeStations(Repeatability& out) {
  const std::size_t stations = out.station_s_m.size();
  out.std_m.assign(stations, kMetricNaN);
  out.spread_m.assign(stations, kMetricNaN);
  double std_sum = 0.0;
  for (std::size_t k = 0; k < stations; ++k) {
    int n = 0;
    double sum = 0.0, lo = kInf, hi = -kInf;
    for (double v : out.offsets_m[k]) {
      if (std::isnan(v)) continue;
      ++n;
      sum += v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (n < 2) continue;
    const double mean = sum / n;
    double ss = 0.0;
    for (double v : out.offsets_m[k]) {
      if (!std::isnan(v)) ss += (v - mean) * (v - mean);
    }
    out.std_m[k] = std::sqrt(ss / (n - 1));
    out.spread_m[k] = hi - lo;
    std_sum += out.std_m[k];
    out.max_spread_m = MaxSkipNaN(out.max_spread_m, out.spread_m[k]);
    ++out.stations_used;
  }
  if (out.stations_used > 0) out.repeatability_m = std_sum / out.stations_used;
}

}  // namespace

Repeatability RepeatabilityFromSeries(double path_length, bool path_empty,
                                      const std::vector<int>& run_ids,
                                      const std::vector<RunSeries>& series,
                                      const MetricsConfig& config) {
  Repeatability out;
  out.station_spacing_m = config.station_spacing;
  out.runs = run_ids;
  if (path_empty) return out;
  const double spacing = config.station_spacing;
  const std::size_t stations =
      static_cast<std::size_t>(std::floor(path_length / spacing + 1e-9)) + 1;
  out.station_s_m.resize(stations);
  for (std::size_t k = 0; k < stations; ++k) out.station_s_m[k] = static_cast<double>(k) * spacing;
  out.offsets_m.assign(stations, std::vector<double>(series.size(), kMetricNaN));
  for (std::size_t r = 0; r < series.size(); ++r)
    InterpolateRunOffsets(series[r], r, spacing, stations, out);
  SummarizeStations(out);
  return out;
}

}  // namespace internal

Repeatability ComputeRepeatability(const TeachTrace& teach, const std::vector<RunTrace>& runs,
                                   const MetricsConfig& config) {
  internal::TeachIndex index(teach, config);
  std::vector<RunSeries> series;
  std::vector<int> ids;
  for (const RunTrace& run : runs) {
    series.push_back(internal::Series(index, run, config, /*with_localization=*/false));
    ids.push_back(run.run);
  }
  return internal::RepeatabilityFromSeries(index.path.length(), index.path.empty(), ids, series,
                                           config);
}

void WriteRepeatabilityCsv(const std::filesystem::path& path, const Repeatability& r) {
  std::vector<std::string> header = {"s_m"};
  for (int run : r.runs) header.push_back("offset_run" + std::to_string(run) + "_m");
  header.push_back("std_m");
  header.push_back("spread_m");
  io::CsvWriter csv(path, header);
  std::vector<io::CsvCell> row;
  for (std::size_t k = 0; k < r.station_s_m.size(); ++k) {
    row.clear();
    row.emplace_back(r.station_s_m[k]);
    for (double v : r.offsets_m[k]) row.emplace_back(RoundTenthMm(v));
    row.emplace_back(RoundTenthMm(r.std_m[k]));
    row.emplace_back(RoundTenthMm(r.spread_m[k]));
    csv.AddRow(row);
  }
  csv.Commit();
}

}  // namespace retrace::bench
