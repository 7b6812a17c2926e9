#include "bench/compare/comparison_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "bench/metrics/provenance.hpp"
#include "core/check.hpp"
#include "core/config.hpp"
#include "core/format.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string ModeName(MapMode mode) { return std::string(core::EnumName(mode)); }

// The reference column's name.
std::string ReferenceName(const Comparison& c) { return c.input.Label(c.reference_index); }

nlohmann::json IntervalJson(const MeanInterval& m) {
  return {{"n", m.n},
          {"mean", io::JsonNumber(m.mean)},
          {"sd", io::JsonNumber(m.sd)},
          {"ci95", {io::JsonNumber(m.lower), io::JsonNumber(m.upper)}}};
}

// Three significant digits, no exponent for the magnitudes the metrics take; "n/a" for
// undefined values. `sign` writes a "+" on positive numbers (differences).
std::string Format(double v, bool sign = false) {
  if (!std::isfinite(v)) return "n/a";
  if (v == 0.0) {
    v = 0.0;       // no "-0"
    sign = false;  // nor "+0"
  }
  const double magnitude = std::abs(v);
  if (magnitude >= 1e4 || (magnitude > 0.0 && magnitude < 1e-3))
    return core::Printf(sign ? "%+.2e" : "%.2e", v);
  if (magnitude >= 1000.0) return core::Printf(sign ? "%+.0f" : "%.0f", v);
  return core::Printf(sign ? "%+.3g" : "%.3g", v);
}

// "mean [lower, upper]"; the interval is "n/a" with fewer than two values.
std::string Cell(const MeanInterval& m, bool sign = false) {
  if (m.n == 0) return "n/a";
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "[" + std::string(...).
  std::string cell = Format(m.mean, sign);
  if (m.n >= 2) {
    cell.append(" [")
        .append(Format(m.lower, sign))
        .append(", ")
        .append(Format(m.upper, sign))
        .append("]");
  } else {
    cell.append(" [n/a]");
  }
  return cell;
}

std::string Label(const ComparedMetric& metric) {
  return metric.label + (metric.timing ? " (timing)" : "");
}

// "1, 2, ..., 8" or "1–8" for consecutive seeds.
std::string SeedList(const std::vector<std::uint64_t>& seeds) {
  bool consecutive = seeds.size() > 2;
  for (std::size_t i = 1; i < seeds.size(); ++i) consecutive &= seeds[i] == seeds[i - 1] + 1;
  if (consecutive) return std::to_string(seeds.front()) + "–" + std::to_string(seeds.back());
  std::string out;
  for (std::size_t i = 0; i < seeds.size(); ++i) out += (i ? ", " : "") + std::to_string(seeds[i]);
  return out;
}

std::string OutcomeText(const std::array<int, 4>& counts) {
  std::string out;
  for (const auto& [outcome, name] : core::EnumTraits<Outcome>::kNames) {
    const int n = counts[static_cast<std::size_t>(outcome)];
    if (n == 0) continue;
    out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + std::string(name);
  }
  return out.empty() ? "no runs" : out;
}

}  // namespace

const std::vector<ComparedMetric>& ComparedMetrics() {
  // Table order: does it work, how well does it follow and localize, how repeatable, how it
  // treats people, what it costs. Maxima are the max over a seed's runs, averaged over seeds.
  static const std::vector<ComparedMetric> kMetrics = {
      {"success_rate", "success_rate", "", "success rate", "fraction", false, false},
      {"tracking_error_m.pooled.rms", "tracking_error_m.pooled.rms", "", "tracking error RMS", "m",
       false, false},
      {"tracking_error_m.pooled.max", "tracking_error_m.pooled.max", "", "tracking error max", "m",
       false, false},
      {"localization_error_m.pooled.rms", "localization_error_m.pooled.rms", "",
       "localization error RMS", "m", false, false},
      {"localization_error_m.pooled.max", "localization_error_m.pooled.max", "",
       "localization error max", "m", false, false},
      {"repeatability_m", "repeatability_m", "", "repeatability", "m", false, false},
      {"repeatability_max_spread_m", "repeatability_max_spread_m", "", "repeatability max spread",
       "m", false, false},
      {"switch_error.max_m", "switch_error.max_m", "", "map-switch error max", "m", false, true},
      {"map_quality.distortion_m.rms", "map_quality.distortion_m.rms", "", "map distortion RMS",
       "m", false, false},
      {"map_quality.agreement", "map_quality.agreement", "", "map agreement with the world",
       "fraction", false, false},
      {"lost_fraction.pooled", "lost_fraction.pooled", "", "lost fraction", "fraction", false,
       false},
      {"dynamic_points.rejected_fraction", "dynamic_points.rejected_fraction", "",
       "beams rejected as dynamic", "fraction", false, false},
      {"progress_fraction", "mean_progress_m", "taught_path_length_m", "progress",
       "fraction of route", false, false},
      {"collisions.pedestrian_incidents_per_run", "collisions.pedestrian_incidents", "runs",
       "pedestrian collisions", "incidents per run", false, false},
      {"collisions.pedestrian_incidents_robot_driving_per_run",
       "collisions.pedestrian_incidents_robot_driving", "runs",
       "pedestrian collisions, robot driving into them", "incidents per run", false, false},
      {"social.intimate_time_s", "social.intimate_time_s", "", "time in pedestrians' intimate zone",
       "s per run", false, false},
      {"social.personal_time_s", "social.personal_time_s", "", "time in pedestrians' personal zone",
       "s per run", false, false},
      {"social.min_ttc_s", "social.min_ttc_s", "", "min time to collision", "s", false, false},
      {"social.path_efficiency", "social.path_efficiency", "", "path efficiency", "fraction", false,
       false},
      {"social.time_efficiency", "social.time_efficiency", "", "time efficiency", "fraction", false,
       false},
      {"social.jerk_m_s3.rms", "social.jerk_m_s3.rms", "", "jerk RMS", "m/s³", false, false},
      {"social.crowd.blocked_per_run", "social.crowd.blocked", "runs",
       "pedestrians blocked by the robot", "per run", false, false},
      {"social.crowd.wait_time_s_per_run", "social.crowd.wait_time_s", "runs",
       "pedestrians' waiting for the robot", "s per run", false, false},
      {"cpu.localizer_update_mean_ms", "cpu.localizer_update_mean_ms", "", "localizer update time",
       "ms", true, false},
  };
  return kMetrics;
}

double ComparedValue(const ComparedMetric& metric, MapMode mode,
                     const std::map<std::string, double>& flat) {
  if (metric.switching_only && !SwitchesMaps(mode)) return kNaN;
  const auto value = flat.find(metric.source);
  if (value == flat.end()) return kNaN;
  if (metric.divisor.empty()) return value->second;
  const auto divisor = flat.find(metric.divisor);
  if (divisor == flat.end() || !(std::abs(divisor->second) > 0.0)) return kNaN;
  return value->second / divisor->second;
}

std::string ComparisonInput::Label(std::size_t m) const {
  return m < labels.size() ? labels[m] : ModeName(modes[m]);
}

Comparison Compare(ComparisonInput input) {
  const std::size_t n_modes = input.modes.size();
  const std::size_t n_seeds = input.seeds.size();
  RETRACE_CHECK(input.flat.size() == n_modes);
  for (const auto& per_mode : input.flat) RETRACE_CHECK(per_mode.size() == n_seeds);
  Comparison out;
  const auto reference = std::find(input.modes.begin(), input.modes.end(), input.reference);
  RETRACE_CHECK(reference != input.modes.end());
  out.reference_index = static_cast<std::size_t>(reference - input.modes.begin());

  out.outcomes.assign(n_modes, {});
  for (std::size_t m = 0; m < n_modes; ++m) {
    for (const auto& flat : input.flat[m]) {
      for (const auto& [outcome, name] : core::EnumTraits<Outcome>::kNames) {
        const auto count = flat.find("outcomes." + std::string(name));
        if (count != flat.end() && std::isfinite(count->second)) {
          out.outcomes[m][static_cast<std::size_t>(outcome)] +=
              static_cast<int>(std::lround(count->second));
        }
      }
    }
  }

  for (const ComparedMetric& metric : ComparedMetrics()) {
    MetricComparison row;
    row.metric = metric;
    row.per_seed.assign(n_modes, std::vector<double>(n_seeds, kNaN));
    for (std::size_t m = 0; m < n_modes; ++m) {
      for (std::size_t s = 0; s < n_seeds; ++s) {
        row.per_seed[m][s] = ComparedValue(metric, input.modes[m], input.flat[m][s]);
      }
      row.summary.push_back(MeanConfidenceInterval(row.per_seed[m], kComparisonConfidence));
    }
    const bool reference_defined = !metric.switching_only || SwitchesMaps(input.reference);
    for (std::size_t m = 0; m < n_modes; ++m) {
      const bool defined = !metric.switching_only || SwitchesMaps(input.modes[m]);
      if (m == out.reference_index || !defined || !reference_defined) {
        row.vs_reference.emplace_back();
      } else {
        row.vs_reference.push_back(ComparePaired(row.per_seed[m], row.per_seed[out.reference_index],
                                                 kComparisonConfidence));
      }
    }
    out.metrics.push_back(std::move(row));
  }
  out.input = std::move(input);
  return out;
}

nlohmann::json ComparisonJson(const Comparison& c) {
  const ComparisonInput& in = c.input;
  nlohmann::json j;
  j["scenario"] = in.scenario_name;
  j["scenario_file"] = in.scenario_file;
  Provenance provenance;
  provenance.command_line = in.command_line;
  provenance.git_revision = in.git_revision;
  provenance.wall_time_s = in.wall_time_s;
  WriteProvenance(provenance, &j);
  j["seeds"] = in.seeds;
  j["repeats"] = in.repeats;
  j["confidence"] = kComparisonConfidence;
  j["reference"] = ReferenceName(c);
  j["metrics"] = nlohmann::json::array();
  for (const MetricComparison& row : c.metrics) {
    j["metrics"].push_back({{"key", row.metric.key},
                            {"label", row.metric.label},
                            {"unit", row.metric.unit},
                            {"timing", row.metric.timing}});
  }
  j["modes"] = nlohmann::json::object();
  for (std::size_t m = 0; m < in.modes.size(); ++m) {
    nlohmann::json mode;
    mode["outcomes"] = nlohmann::json::object();
    for (const auto& [outcome, name] : core::EnumTraits<Outcome>::kNames) {
      mode["outcomes"][std::string(name)] = c.outcomes[m][static_cast<std::size_t>(outcome)];
    }
    for (const MetricComparison& row : c.metrics) {
      nlohmann::json value = IntervalJson(row.summary[m]);
      value["per_seed"] = nlohmann::json::array();
      for (double v : row.per_seed[m]) value["per_seed"].push_back(io::JsonNumber(v));
      if (row.vs_reference[m]) {
        const PairedComparison& p = *row.vs_reference[m];
        nlohmann::json diff = IntervalJson(p.difference);
        diff["significant"] = p.significant;
        diff["ratio_of_means"] = io::JsonNumber(p.ratio_of_means);
        value["vs_reference"] = std::move(diff);
      }
      mode[row.metric.key] = std::move(value);
    }
    j["modes"][in.Label(m)] = std::move(mode);
  }
  return j;
}

namespace {

// What was run and how to read the table: seeds, runs, the intervals, the differences.
void WriteMarkdownIntro(std::ostringstream& md, const Comparison& c) {
  const ComparisonInput& in = c.input;
  const std::string ref = ReferenceName(c);
  const std::size_t n_seeds = in.seeds.size();
  md << "## Map modes compared: " << in.scenario_name << "\n\n";
  md << n_seeds << " seeds × " << in.repeats << " playback run" << (in.repeats == 1 ? "" : "s")
     << " per mode (scenario seeds " << SeedList(in.seeds)
     << "). Each seed has one teaching drive that builds the maps of every mode, and playback run "
        "i uses the "
        "same seed in every mode, so the modes are compared seed by seed (paired).\n\n";
  md << "Each cell is the mean over the seeds of a seed's value (the metric over its " << in.repeats
     << " run" << (in.repeats == 1 ? "" : "s")
     << "; maxima are a seed's maximum) with the 95 % confidence "
     << "interval of that mean in brackets: Student t with " << (n_seeds - 1) << " degree"
     << (n_seeds == 2 ? "" : "s")
     << " of freedom, mean ± t·SD/√n. If the study were repeated with new seeds, intervals built "
        "this "
        "way would contain the true mean 95 % of the time. Differences are per seed, mode − "
     << ref
     << ", with the interval of their mean; * marks a significant difference (its interval "
        "excludes 0). "
     << "Ratios are mean(mode) / mean(" << ref << ").\n\n";
}

// The table: a row per metric, each mode's interval, then each other mode's difference from the
// reference and ratio to it.
void WriteMarkdownTable(std::ostringstream& md, const Comparison& c) {
  const ComparisonInput& in = c.input;
  const std::string ref = ReferenceName(c);
  md << "| metric | unit |";
  for (std::size_t m = 0; m < in.modes.size(); ++m) md << " " << in.Label(m) << " |";
  for (std::size_t m = 0; m < in.modes.size(); ++m) {
    if (m == c.reference_index) continue;
    md << " " << in.Label(m) << " − " << ref << " | " << in.Label(m) << " / "
       << ref << " |";
  }
  md << "\n|---|---|";
  const std::size_t columns =
      in.modes.size() + 2 * (in.modes.size() - 1);  // values, then difference and ratio
  for (std::size_t k = 0; k < columns; ++k) md << "---:|";
  md << "\n";
  for (const MetricComparison& row : c.metrics) {
    md << "| " << Label(row.metric) << " | " << row.metric.unit << " |";
    for (const MeanInterval& s : row.summary) md << " " << Cell(s) << " |";
    for (std::size_t m = 0; m < in.modes.size(); ++m) {
      if (m == c.reference_index) continue;
      if (!row.vs_reference[m]) {
        md << " n/a | n/a |";
        continue;
      }
      const PairedComparison& p = *row.vs_reference[m];
      md << " " << Cell(p.difference, true) << (p.significant ? " *" : "") << " | "
         << Format(p.ratio_of_means) << " |";
    }
    md << "\n";
  }
}

// The runs' outcomes per mode, then each other mode's significant differences from the
// reference.
void WriteMarkdownFindings(std::ostringstream& md, const Comparison& c) {
  const ComparisonInput& in = c.input;
  const std::string ref = ReferenceName(c);
  md << "\nRun outcomes (" << in.seeds.size() * static_cast<std::size_t>(in.repeats)
     << " runs per mode):";
  for (std::size_t m = 0; m < in.modes.size(); ++m) {
    md << (m ? ";" : "") << " " << in.Label(m) << " " << OutcomeText(c.outcomes[m]);
  }
  md << ".\n\n";
  for (std::size_t m = 0; m < in.modes.size(); ++m) {
    if (m == c.reference_index) continue;
    std::string significant;
    for (const MetricComparison& row : c.metrics) {
      if (!row.vs_reference[m] || !row.vs_reference[m]->significant) continue;
      significant += (significant.empty() ? "" : ", ") + Label(row.metric) + " (" +
                     Format(row.vs_reference[m]->difference.mean, true) + " " + row.metric.unit +
                     ")";
    }
    md << "Significant differences, " << in.Label(m) << " − " << ref << ": "
       << (significant.empty() ? "none" : significant) << ".\n";
  }
}

// What repeatability and n/a mean.
void WriteMarkdownNotes(std::ostringstream& md) {
  md << "\nRepeatability: the mean, over stations along the taught path (metrics.station_spacing "
        "apart), "
        "of the standard deviation of the runs' lateral offsets; max spread: the largest max − min "
        "there.\n";
  md << "n/a: not defined (map-switch errors exist in the modes that switch maps only; "
        "repeatability needs two "
        "runs; a "
        "ratio needs a non-zero reference mean). Timing rows measure this machine under its load, "
        "not the "
        "navigation.\n";
}

}  // namespace

std::string ComparisonMarkdown(const Comparison& c) {
  std::ostringstream md;
  WriteMarkdownIntro(md, c);
  WriteMarkdownTable(md, c);
  WriteMarkdownFindings(md, c);
  WriteMarkdownNotes(md);
  return md.str();
}

viz::ComparisonFigureData ComparisonFigure(const Comparison& c) {
  viz::ComparisonFigureData data;
  // ASCII only: the figure's Hershey fonts have no "×".
  data.scenario = c.input.scenario_name + " (" + std::to_string(c.input.seeds.size()) +
                  " seeds x " + std::to_string(c.input.repeats) +
                  (c.input.repeats == 1 ? " run" : " runs") +
                  " per mode; mean and 95% CI over seeds)";
  for (std::size_t m = 0; m < c.input.modes.size(); ++m) {
    viz::ModeMetrics mode;
    mode.mode = c.input.Label(m);
    for (const MetricComparison& row : c.metrics) {
      const MeanInterval& s = row.summary[m];
      mode.metrics.push_back(
          {Label(row.metric) + " (" + row.metric.unit + ")", s.mean, s.lower, s.upper});
    }
    data.modes.push_back(std::move(mode));
  }
  return data;
}

}  // namespace retrace::bench
