#include "bench/crowd/crowd_check.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "core/format.hpp"
#include "io/config_yaml.hpp"
#include "io/csv_writer.hpp"
#include "io/json_writer.hpp"
#include "viz/fundamental_diagram_figure.hpp"

namespace retrace::bench {
namespace {

// v with `decimals` decimals, "-" when not finite.
std::string Fixed(double v, int decimals) {
  return std::isfinite(v) ? core::FixedText(v, decimals) : "-";
}

std::string Percent(double v) { return std::isfinite(v) ? Fixed(100.0 * v, 1) + " %" : "-"; }

std::string FlowLabel(CrowdFlow flow) {
  return flow == CrowdFlow::kOneWay ? "one-way flow" : "two-way flow";
}

void WriteFigure(const CrowdCheck& check, const std::filesystem::path& png) {
  viz::FundamentalDiagramFigureData fig;
  const WeidmannCurve curve;
  const double tolerance = kDiagramTolerance;
  for (double rho = 0.1; rho <= 4.6 + 1e-9; rho += 0.025) {
    const double v = WeidmannSpeed(rho, curve);
    fig.curve_density.push_back(rho);
    fig.curve_speed.push_back(v);
    fig.band_low.push_back((1.0 - tolerance) * v);
    fig.band_high.push_back((1.0 + tolerance) * v);
  }
  fig.curve_label = "Weidmann (1993)";
  fig.band_label = "+-" + Fixed(100.0 * tolerance, 0) + " %";
  std::string rms;
  for (const FundamentalDiagramResult& result : check.flows) {
    viz::SpeedSeries series;
    series.label = FlowLabel(result.flow) + " (mean, bars: +-1 SD)";
    for (const FundamentalDiagramRow& row : result.rows) {
      if (row.spawned) series.points.push_back({row.density, row.mean_speed, row.speed_std});
    }
    fig.series.push_back(std::move(series));
    rms += (rms.empty() ? "" : ", ") + std::string(core::EnumName(result.flow)) + " " +
           Fixed(result.rms_deviation, 3);
  }
  fig.subtitle = "Ring " + Fixed(check.config.width, 1) +
                 " m wide, r = " + Fixed(check.config.pedestrian_radius, 2) + " m, model " +
                 std::string(core::EnumName(check.config.crowd.model)) + "; RMS " + rms + " m/s";
  viz::FigureOptions options;
  options.width = 1000;
  viz::RenderFundamentalDiagramFigure(fig, png, options);
}

nlohmann::ordered_json RowJson(const FundamentalDiagramRow& r) {
  nlohmann::ordered_json row;
  row["requested_density"] = r.requested_density;
  row["count"] = r.count;
  row["density"] = r.density;
  row["spawned"] = r.spawned;
  if (!r.note.empty()) row["note"] = r.note;
  row["mean_speed"] = io::JsonNumber(r.spawned ? r.mean_speed : NAN);
  row["speed_std"] = io::JsonNumber(r.spawned ? r.speed_std : NAN);
  row["mean_abs_speed"] = io::JsonNumber(r.spawned ? r.mean_abs_speed : NAN);
  row["weidmann_speed"] = r.weidmann_speed;
  row["relative_deviation"] = io::JsonNumber(r.spawned ? r.relative_deviation : NAN);
  row["samples"] = r.samples;
  row["lattice_spacing"] = r.lattice_spacing;
  row["misaligned_starts"] = r.misaligned_starts;
  row["yields"] = r.yields;
  row["goals_abandoned"] = r.goals_abandoned;
  row["encounters"] = r.encounters;
  row["closest_approach"] = io::JsonNumber(r.spawned ? r.closest_approach : NAN);
  row["closest_approach_p05"] = io::JsonNumber(r.spawned ? r.closest_approach_p05 : NAN);
  return row;
}

nlohmann::ordered_json ToJson(const CrowdCheck& check, std::uint64_t seed,
                              const std::vector<std::string>& overrides) {
  const FundamentalDiagramConfig& config = check.config;
  nlohmann::ordered_json j;
  j["check"] = "fundamental diagram, ring corridor, one-way and two-way flow";
  j["seed"] = seed;
  j["overrides"] = overrides;
  const WeidmannCurve curve;
  j["weidmann"] = {
      {"free_speed", curve.free_speed}, {"gamma", curve.gamma}, {"max_density", curve.max_density}};
  j["tolerance"] = kDiagramTolerance;
  j["parameters"] = {{"inner_radius", config.inner_radius},
                     {"width", config.width},
                     {"outer_radius", config.outer_radius()},
                     {"area", config.area()},
                     {"pedestrian_radius", config.pedestrian_radius},
                     {"speed_mean", config.speed_mean},
                     {"speed_std", config.speed_std},
                     {"warmup", config.warmup},
                     {"duration", config.duration},
                     {"sample_period", config.sample_period},
                     {"time_step", config.time_step},
                     {"encounter_radius", kEncounterRadius},
                     {"speed_measured", "velocity along the ring's tangent, walking direction"}};
  j["config_yaml"] = io::ConfigToYaml(config);
  nlohmann::ordered_json flows = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < check.flows.size(); ++k) {
    const FundamentalDiagramResult& result = check.flows[k];
    nlohmann::ordered_json flow;
    flow["flow"] = std::string(core::EnumName(result.flow));
    flow["clockwise_fraction"] = ClockwiseFraction(result.flow);
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const FundamentalDiagramRow& r : result.rows) rows.push_back(RowJson(r));
    flow["rows"] = rows;
    flow["rms_deviation"] = io::JsonNumber(result.rms_deviation);
    flow["max_abs_deviation"] = io::JsonNumber(result.max_abs_deviation);
    flow["rows_within"] = result.rows_within;
    flow["pass"] = result.pass;
    flow["seconds"] = check.flow_seconds[k];
    flows.push_back(flow);
  }
  j["flows"] = flows;
  j["pass"] = check.pass;
  return j;
}

void WriteCsv(const CrowdCheck& check, const std::filesystem::path& path) {
  io::CsvWriter csv(path, {"flow", "requested_density", "count", "density", "spawned", "mean_speed",
                           "speed_std", "mean_abs_speed", "weidmann_speed", "relative_deviation",
                           "samples", "encounters", "closest_approach", "closest_approach_p05"});
  const double nan = std::nan("");
  for (const FundamentalDiagramResult& result : check.flows) {
    for (const FundamentalDiagramRow& r : result.rows) {
      csv.AddRow({std::string(core::EnumName(result.flow)), r.requested_density, r.count, r.density,
                  r.spawned, r.spawned ? r.mean_speed : nan, r.spawned ? r.speed_std : nan,
                  r.spawned ? r.mean_abs_speed : nan, r.weidmann_speed,
                  r.spawned ? r.relative_deviation : nan, static_cast<long long>(r.samples),
                  static_cast<long long>(r.encounters), r.spawned ? r.closest_approach : nan,
                  r.spawned ? r.closest_approach_p05 : nan});
    }
  }
  csv.Commit();
}

std::string Table(const FundamentalDiagramResult& result) {
  std::string out = FlowLabel(result.flow) + ":\n";
  char line[256];
  std::snprintf(line, sizeof(line), "%9s %6s %9s %10s %9s %10s %9s %10s\n", "rho(/m2)", "count",
                "v_sim", "sd", "v_weid", "dev", "closest", "");
  out += line;
  for (const FundamentalDiagramRow& r : result.rows) {
    if (!r.spawned) {
      std::snprintf(line, sizeof(line), "%9.3f %6d  not spawned: %s\n", r.density, r.count,
                    r.note.c_str());
    } else {
      const bool in_band = std::abs(r.relative_deviation) <= result.tolerance;
      std::snprintf(line, sizeof(line), "%9.3f %6d %9.3f %10.3f %9.3f %10s %9s %10s\n", r.density,
                    r.count, r.mean_speed, r.speed_std, r.weidmann_speed,
                    Percent(r.relative_deviation).c_str(), Fixed(r.closest_approach, 2).c_str(),
                    in_band ? "" : "outside");
    }
    out += line;
  }
  out += "RMS deviation: " + Fixed(result.rms_deviation, 3) + " m/s; largest " +
         Percent(result.max_abs_deviation) + "; " + std::to_string(result.rows_within) + " of " +
         std::to_string(result.rows.size()) + " densities within " +
         Fixed(100.0 * result.tolerance, 0) + " %" + (result.pass ? "  pass" : "  FAIL") + "\n";
  return out;
}

// The items of a comma-separated list, each without surrounding spaces ("" gives one empty item).
std::vector<std::string> CommaSeparated(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    std::string item = text.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.erase(item.begin());
    while (!item.empty() && item.back() == ' ') item.pop_back();
    out.push_back(std::move(item));
    start = end + 1;
  }
  return out;
}

}  // namespace

std::vector<double> ParseDensityList(const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : CommaSeparated(text)) {
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || ec != std::errc() || ptr != item.data() + item.size()) {
      throw core::ConfigError("densities", "'" + item + "' is not a number (persons/m²)");
    }
    out.push_back(v);
  }
  ValidateDensities(out);
  return out;
}

std::vector<CrowdFlow> ParseFlowList(const std::string& text) {
  std::vector<CrowdFlow> out;
  for (const std::string& item : CommaSeparated(text)) {
    const std::optional<CrowdFlow> flow = core::ParseEnum<CrowdFlow>(item);
    if (!flow) {
      throw core::ConfigError(
          "flows", "'" + item + "' is not a flow (" + core::EnumNameList<CrowdFlow>() + ")");
    }
    if (std::find(out.begin(), out.end(), *flow) != out.end()) {
      throw core::ConfigError("flows", "'" + item + "' is given twice");
    }
    out.push_back(*flow);
  }
  return out;
}

CrowdCheck RunCrowdCheck(
    const CrowdCheckRequest& request,
    const std::function<void(const FundamentalDiagramRow& row, std::size_t done)>& progress) {
  CrowdCheck check;
  check.config = ReadFundamentalDiagramConfig(request.overrides);
  if (request.duration > 0.0) check.config.duration = request.duration;
  if (request.warmup >= 0.0) check.config.warmup = request.warmup;
  check.config.Validate();
  ValidateDensities(request.densities);
  if (request.flows.empty()) throw core::ConfigError("flows", "needs at least one flow");
  const auto start = std::chrono::steady_clock::now();
  std::size_t done = 0;
  check.pass = true;
  for (const CrowdFlow flow : request.flows) {
    const auto flow_start = std::chrono::steady_clock::now();
    check.flows.push_back(RunFundamentalDiagram(check.config, flow, request.densities, request.seed,
                                                [&](const FundamentalDiagramRow& row) {
                                                  ++done;
                                                  if (progress) progress(row, done);
                                                }));
    check.flow_seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - flow_start).count());
    check.pass = check.pass && check.flows.back().pass;
  }
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return check;
}

void WriteCrowdCheckFolder(const std::filesystem::path& out, const CrowdCheck& check,
                           const CrowdCheckRequest& request) {
  std::filesystem::create_directories(out);
  WriteCsv(check, out / "fundamental_diagram.csv");
  io::WriteJsonAtomic(out / "crowd_check.json", ToJson(check, request.seed, request.overrides));
  WriteFigure(check, out / "fundamental_diagram.png");
}

std::string CrowdCheckSummary(const CrowdCheck& check, const std::filesystem::path& out) {
  std::string text;
  for (const FundamentalDiagramResult& result : check.flows) text += Table(result);
  std::size_t rows = 0;
  for (const FundamentalDiagramResult& result : check.flows) rows += result.rows.size();
  return text + "simulated " + std::to_string(rows) + " densities x " +
         Fixed(check.config.warmup + check.config.duration, 0) + " s in " +
         Fixed(check.seconds, 1) + " s -> " + out.string() + "\n";
}

}  // namespace retrace::bench
