#include "bench/calibration/lidar_calibration_run.hpp"

#include <cmath>
#include <cstdio>

#include "bench/calibration/lidar_calibration_figure.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_run_options.hpp"
#include "bench/replay/log_streams.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/config_override.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {

namespace {

std::string PartRow(const std::string& name, const LidarFit& fit) {
  const nav::BeamMixture& m = fit.result.mixture;
  char line[256];
  std::snprintf(line, sizeof line,
                "%-12s %8.1f %8.1f %8zu %7.4f %7.4f %7.4f %7.4f %9.4f %9.3f %7.4f %5d",
                name.c_str(), fit.from_s, fit.to_s, fit.result.beams, m.z_hit, m.z_short, m.z_max,
                m.z_rand, m.sigma_hit, m.lambda_short, m.hit_offset, fit.result.iterations);
  return line;
}

// How far apart the halves' fits are: weights in points, σ and λ relative to the whole's.
std::string HalvesSpread(const LidarCalibration& c) {
  const nav::BeamMixture& a = c.first_half.result.mixture;
  const nav::BeamMixture& b = c.second_half.result.mixture;
  const nav::BeamMixture& w = c.whole.result.mixture;
  const auto points = [](double x, double y) {
    return core::FixedText(100.0 * std::abs(x - y), 2);
  };
  const auto percent = [](double x, double y, double whole) {
    return whole > 0.0 ? core::FixedText(100.0 * std::abs(x - y) / whole, 1) + " %" : "-";
  };
  return "halves differ by: z_hit " + points(a.z_hit, b.z_hit) + ", z_short " +
         points(a.z_short, b.z_short) + ", z_max " + points(a.z_max, b.z_max) + ", z_rand " +
         points(a.z_rand, b.z_rand) + " points; sigma_hit " +
         percent(a.sigma_hit, b.sigma_hit, w.sigma_hit) + ", lambda_short " +
         (a.lambda_short == b.lambda_short
              ? std::string("0 %")
              : percent(a.lambda_short, b.lambda_short, w.lambda_short)) +
         " of the whole's; hit offset " +
         core::FixedText(100.0 * std::abs(a.hit_offset - b.hit_offset), 1) + " cm";
}

double Share(std::size_t part, std::size_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

std::string UnmappedRow(const std::string& name, const UnmappedPart& part) {
  const UnmappedFit& f = part.fit;
  char line[256];
  std::snprintf(line, sizeof line,
                "%-12s %8.1f %8.1f %8zu %6.1f %% %8zu %9.0f %7.2f %7zu %7zu %8.0f %8.4f",
                name.c_str(), part.from_s, part.to_s, f.beams,
                100.0 * Share(f.short_readings, f.beams), f.unknown_hits, f.unknown_exposure_m,
                f.unknown_free_path, f.band_hits, f.static_band_hits, f.band_exposure_m, f.density);
  return line;
}

// What the map does not hold: one row per part.
std::vector<std::string> UnmappedReport(const LidarCalibration& c) {
  return {
      "what the map does not hold (readings short of the map by more than 3 sigma_hit less "
      "the offset, where they end):",
      "part         from (s)   to (s)    beams   short  unknown  exposure  free_path   band "
      " static exposure  density",
      UnmappedRow("whole", c.unmapped_whole),
      UnmappedRow("first half", c.unmapped_first_half),
      UnmappedRow("second half", c.unmapped_second_half),
      "(exposure: m of the rays in unknown cells and in the clutter's band; band: readings "
      "ending short in it, static: of those on something that stays; free_path in m, "
      "density of static objects per m^2, of mean width " +
          core::FixedText(c.unmapped_whole.fit.mean_width_m, 2) + " m)"};
}

// The simulated world that reproduces the real estimates, and how close its scans came.
std::string WorldLine(const UnmappedFit& real, const WorldInference& inference) {
  const UnmappedFit& sim = inference.simulated;
  const std::string unknown =
      inference.free_path > 0.0 ? "unknown cells filled at a free path of " +
                                      core::FixedText(inference.free_path, 2) + " m"
      : inference.unknown_hits_enough
          ? std::string("unknown cells left open (rays cross them farther than the LiDAR reaches)")
          : "unknown cells left open (fewer than " + std::to_string(kMinUnknownHitsPerHalf) +
                " readings end in them in a half of the window)";
  return "simulated world: " + unknown + ", static clutter " +
         core::FixedText(inference.density, 4) + " per m^2 (" +
         std::to_string(inference.simulations) +
         (inference.simulations == 1 ? " simulation" : " simulations") +
         (inference.converged ? "" : ", not within 5 % and 10 %") +
         "); its scans estimate a free path of " + core::FixedText(sim.unknown_free_path, 2) +
         " m and " + core::FixedText(sim.density, 4) + " per m^2 (real " +
         core::FixedText(real.unknown_free_path, 2) + " m, " + core::FixedText(real.density, 4) +
         "), short readings " + core::FixedText(100.0 * Share(sim.short_readings, sim.beams), 1) +
         " % (real " + core::FixedText(100.0 * Share(real.short_readings, real.beams), 1) + " %)";
}

// The fit report: what was used, then one row per part and the halves' spread.
std::vector<std::string> FitReport(const LidarCalibration& c, const std::string& log_name,
                                   const std::filesystem::path& teach_dir) {
  const CalibrationBeams& b = c.beams;
  std::vector<std::string> lines = {
      log_name + ": " + std::to_string(b.scans) + " scans (" + core::FixedText(b.first_s, 1) +
          " to " + core::FixedText(b.last_s, 1) + " s of log time, as --from/--to), " +
          std::to_string(b.beams) + " beams",
      "map: " + teach_dir.string() + "; expected range known for " +
          std::to_string(b.samples.size() + b.invalid) + " beams (" + std::to_string(b.unknown) +
          " unknown, " + std::to_string(b.invalid) + " of the known below range_min and left out)",
      "LiDAR range " + core::FixedText(b.range_min, 2) + " to " + core::FixedText(b.range_max, 2) +
          " m; EM of Probabilistic Robotics Table 6.2",
      "part         from (s)   to (s)    beams   z_hit z_short   z_max  z_rand sigma_hit "
      "lambda_sh  offset  iter",
      PartRow("whole", c.whole),
      PartRow("first half", c.first_half),
      PartRow("second half", c.second_half),
      HalvesSpread(c),
      "(sigma_hit and the hit offset in m, lambda_short in 1/m; times: s since the log's first "
      "scan)",
      "hit offset: the readings' Gaussian is centred " +
          core::FixedText(c.whole.result.mixture.hit_offset, 3) +
          " m beyond the cast range z*, a property of the grid map (the cast stops at the face "
          "of the first occupied cell), not of the sensor: not part of sim.lidar.noise"};
  for (const std::string& line : UnmappedReport(c)) lines.push_back(line);
  return lines;
}

// The YAML file: the fit report as comments, then the sim.lidar.noise block.
std::string CalibrationYaml(const std::vector<std::string>& report,
                            const sim::LidarNoiseConfig& noise, const WorldInference& world,
                            const ClutterConfig& clutter, const std::string& command_line) {
  std::string text = "# retrace calibrate-lidar: the simulated LiDAR's noise fitted to a log\n";
  text += "# " + command_line + "\n#\n";
  for (const std::string& line : report) text += "# " + line + "\n";
  text +=
      "#\n# The block below is the whole fit's mixture in sim.lidar.noise keys (docs/METHOD.md)\n"
      "# without its short returns (short_probability 0: the world's unknown cells and clutter\n"
      "# make them; without those, set it to the fit's z_short), then the world's settings.\n"
      "# --config takes this file as it is; the lines above are comments.\n";
  text += "sim:\n  lidar:\n    noise:\n";
  sim::LidarNoiseConfig copy = noise;
  auto write_key = [&](std::string_view key, double value) {
    text += "      " + std::string(key) + ": " + core::FormatNumber(value) + "\n";
  };
  copy.Reflect(write_key);
  text += "  unknown_free_path: " + core::FormatNumber(world.free_path) + "\n";
  text += "clutter:\n  density: " + core::FormatNumber(world.density) + "\n";
  text += "  band: " + core::FormatNumber(clutter.band) + "\n";
  text += "  clearance: " + core::FormatNumber(clutter.clearance) + "\n";
  text += "  kinds: [";
  for (std::size_t i = 0; i < clutter.kinds.size(); ++i)
    text += (i > 0 ? ", " : "") + std::string(core::EnumName(clutter.kinds[i]));
  text += "]\n";
  return text;
}

std::filesystem::path FigurePath(const LidarCalibrationRequest& request) {
  if (request.figure) return *request.figure;
  std::filesystem::path png = request.out;
  return png.replace_extension(".png");
}

}  // namespace

LidarCalibrationRun CalibrateLidar(const LidarCalibrationRequest& request) {
  RequireWindow(request.window);
  std::vector<io::ConfigOverride> overrides;
  for (const std::string& text : request.overrides) overrides.push_back(io::ParseOverride(text));
  LidarCalibrationRun c;
  c.request = request;
  c.clutter = LoadLogConfig(request.config, overrides).clutter;
  const ModeTeach teach = ReadTeachFolder(request.teach_dir, MapMode::kConsistent);
  RequireWorldMap(teach, request.teach_dir, TeachFolderMode(request.teach_dir));
  const logs::LogIndex index = logs::IndexLog(request.log, request.streams);
  logs::RequireUsable(index);
  c.log_name = index.name;
  const LogStreams streams =
      PrepareLogStreams(index, LogConfig{}, request.synthetic_odometry, request.reference);
  LidarCalibrationOptions options;
  options.min_beams_per_half = request.min_beams;
  options.fit.max_iterations = request.max_iterations;
  c.calibration =
      FitLidarCalibration(CollectCalibrationBeams(index, streams, teach, request.window, c.clutter),
                          index.name, options, c.clutter);
  c.world = InferSimulatedWorld(index, streams, teach, request.teach_dir, request.window,
                                c.calibration, c.clutter);
  c.report = FitReport(c.calibration, index.name, request.teach_dir);
  c.report.push_back(WorldLine(c.calibration.unmapped_whole.fit, c.world));
  c.noise = WorldNoise(c.calibration.whole.result.mixture);
  return c;
}

std::vector<std::string> WriteLidarCalibration(const LidarCalibrationRun& c,
                                               const std::string& command_line) {
  const LidarCalibrationRequest& request = c.request;
  io::WriteFileAtomic(request.out,
                      CalibrationYaml(c.report, c.noise, c.world, c.clutter, command_line));
  if (!request.figures) return {};
  try {
    const std::filesystem::path png = FigurePath(request);
    viz::RenderRangeErrorFigure(
        RangeErrorFigureOf(c.calibration, c.log_name + ", " +
                                              std::to_string(c.calibration.beams.samples.size()) +
                                              " beams against " + request.teach_dir.string()),
        png);
    return {"figure: " + png.string()};
  } catch (const viz::RenderError& e) {
    return {std::string("figure not rendered: ") + e.what()};
  }
}

std::string LidarCalibrationSummary(const LidarCalibrationRun& c) {
  std::string text;
  for (const std::string& line : c.report) text += line + "\n";
  return text + "sim.lidar.noise: " + c.request.out.string();
}

}  // namespace retrace::bench
