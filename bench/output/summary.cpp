#include "bench/output/summary.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/format.hpp"

namespace retrace::bench {
namespace {

// A number for the table, "-" when undefined.
std::string Cell(double v, const char* format = "%.3f") {
  if (!std::isfinite(v)) return "-";
  return core::Printf(format, v);
}

// The scenario's line: route length and how its maps are cut.
std::string ScenarioLine(const Scenario& scenario) {
  const std::vector<double>& switch_points = scenario.config.route.switch_points.value;
  std::string text = "scenario " + scenario.config.name + ": route " +
                     Cell(scenario.route_length, "%.1f") + " m, ";
  if (scenario.switching_online()) {
    text += "switch points online (chosen while teaching)";
  } else {
    text += std::to_string(switch_points.size() + 1) + " partial maps";
  }
  if (scenario.switch_points_auto) {
    text += " (switch points auto:";
    for (std::size_t i = 0; i < switch_points.size(); ++i)
      text += (i ? ", " : " ") + Cell(switch_points[i], "%.1f");
    text += switch_points.empty() ? " none needed)" : " m)";
  }
  if (scenario.config.playback.stack != "retrace") {
    text += "; playback stack: " + scenario.config.playback.stack;
  }
  text += "\n";
  return text;
}

// One row per mode of the main numbers.
std::string MainTable(const std::vector<ModeSummary>& modes) {
  std::string text;
  char line[512];
  std::snprintf(line, sizeof line, "%-12s %8s %9s %9s %9s %9s %9s %9s %9s %7s\n", "mode", "success",
                "track_rms", "track_max", "loc_rms", "loc_max", "repeat", "switch_mx", "coll_ped",
                "rtf");
  text += line;
  for (const ModeSummary& m : modes) {
    if (m.runs == 0) {
      std::snprintf(line, sizeof line, "%-12s teach bundle only\n",
                    std::string(core::EnumName(m.mode)).c_str());
      text += line;
      continue;
    }
    const AggregateMetrics& a = m.aggregate;
    const std::string collisions = std::to_string(a.collisions.pedestrian_incidents) + " (" +
                                   std::to_string(a.collisions.pedestrian_incidents_robot_driving) +
                                   ")";
    std::snprintf(line, sizeof line, "%-12s %8s %9s %9s %9s %9s %9s %9s %9s %7s\n",
                  std::string(core::EnumName(m.mode)).c_str(),
                  (std::to_string(m.successes) + "/" + std::to_string(m.runs)).c_str(),
                  Cell(a.tracking_error_m_pooled.rms).c_str(),
                  Cell(a.tracking_error_m_pooled.max).c_str(),
                  Cell(a.localization_error_m_pooled.rms).c_str(),
                  Cell(a.localization_error_m_pooled.max).c_str(),
                  Cell(a.repeatability.repeatability_m).c_str(), Cell(a.switch_error.max_m).c_str(),
                  collisions.c_str(), Cell(a.cpu.real_time_factor, "%.0f").c_str());
    text += line;
  }
  return text;
}

// The social metrics per behaviour toward the robot, when anyone met behaved otherwise than
// `regular`, and which behaviour stopped the failed runs.
std::string BehaviourLines(const SocialStats& so, int failed) {
  bool others = false;
  for (std::size_t b = 1; b < so.by_behaviour.size(); ++b) others |= so.by_behaviour[b].people > 0;
  if (!others) return "";
  std::string text;
  int stopped = 0;
  for (const auto& [behaviour, name] : core::EnumTraits<sim::RobotBehaviour>::kNames) {
    const BehaviourSocial& b = so.by_behaviour[static_cast<std::size_t>(behaviour)];
    stopped += b.runs_stopped;
    if (b.people == 0) continue;
    text += "  " + std::string(name) + ": " + std::to_string(b.people) + " met, closest " +
            Cell(b.min_gap_m, "%.2f") + " m, " + Cell(b.intimate_time_s, "%.1f") +
            " s intimate / " + Cell(b.personal_time_s, "%.1f") + " s personal per run, " +
            std::to_string(b.crowd.encounters) + " encounters (" + std::to_string(b.crowd.passed) +
            " passed, " + std::to_string(b.crowd.yielded) + " yielded, " +
            std::to_string(b.crowd.blocked) + " blocked)";
    if (b.runs_stopped > 0) {
      text += "; stopped the robot in " + std::to_string(b.runs_stopped) + " run" +
              (b.runs_stopped == 1 ? "" : "s");
    }
    text += "\n";
  }
  if (failed > stopped) {
    text += "  " + std::to_string(failed - stopped) + " failed run" +
            (failed - stopped == 1 ? "" : "s") + " with nobody reacting to the robot in its way\n";
  }
  return text;
}

// How each mode treated the people around it (social metrics, means per run).
std::string SocialLines(const std::vector<ModeSummary>& modes) {
  std::string text;
  for (const ModeSummary& m : modes) {
    if (m.runs == 0) continue;
    const SocialStats& so = m.aggregate.social;
    const CrowdReaction& c = so.crowd;
    text += std::string(core::EnumName(m.mode));
    text += ": within " + Cell(so.intimate_time_s, "%.1f");
    text += " s intimate / " + Cell(so.personal_time_s, "%.1f");
    text += " s personal per run, min TTC " + Cell(so.min_ttc_s, "%.2f");
    text += " s, efficiency path " + Cell(so.path_efficiency, "%.3f");
    text += " time " + Cell(so.time_efficiency, "%.3f");
    text += ", jerk RMS " + Cell(so.jerk_m_s3.rms, "%.2f");
    text += " m/s3; " + std::to_string(c.encounters) + " encounters: ";
    text += std::to_string(c.passed) + " passed, " + std::to_string(c.yielded) + " yielded, ";
    text += std::to_string(c.blocked) + " blocked (waited " + Cell(c.wait_time_s, "%.1f");
    text += " s)";
    if (c.standing > 0) text += ", " + std::to_string(c.standing) + " standing still by design";
    text += "\n" + BehaviourLines(so, m.runs - m.successes);
  }
  return text;
}

// How the localizer held, by its own account, and the largest one-tick move of its estimate.
std::string LocalizerLines(const std::vector<ModeSummary>& modes) {
  std::string text;
  for (const ModeSummary& m : modes) {
    if (m.runs == 0) continue;
    const LocalizerHealth& h = m.aggregate.localizer;
    text += std::string(core::EnumName(m.mode)) + ": localizer lost " +
            Cell(h.lost_time_s, "%.1f") + " s in " + std::to_string(h.lost_spells) + " spells, " +
            std::to_string(h.reacquisitions) + " re-acquisitions (" +
            std::to_string(h.reacquisitions_wrong) + " wrong); largest single-tick jump " +
            Cell(h.max_jump_m, "%.2f") + " m, error increase " +
            Cell(h.max_error_increase_m, "%.2f") + " m; silent failure " +
            Cell(h.silent_failure_time_s, "%.1f") + " s, false alarm " +
            Cell(h.false_alarm_time_s, "%.1f") + " s, off map " + Cell(h.off_map_time_s, "%.1f") +
            " s, " + std::to_string(h.wrong_switches) + " wrong switches\n";
  }
  return text;
}

// How the switching modes' maps were cut, judged on the drive's ground truth.
std::string SwitchingLines(const std::vector<ModeSummary>& modes) {
  std::string text;
  for (const ModeSummary& m : modes) {
    const SwitchingQuality& q = m.aggregate.switching;
    if (!SwitchesMaps(m.mode) || q.maps == 0) continue;
    std::string cut = std::string(core::EnumName(m.mode)) + ": " + std::to_string(q.maps) +
                      " maps (fewest possible " + std::to_string(q.minimum) + "), " +
                      std::to_string(q.revisiting) + " holding a place twice";
    if (!q.switch_travel_m.empty()) {
      cut += "; switches after";
      for (std::size_t i = 0; i < q.switch_travel_m.size(); ++i) {
        cut += (i ? ", " : " ") + Cell(q.switch_travel_m[i], "%.1f");
        if (i < q.reasons.size()) cut += " (" + q.reasons[i] + ")";
      }
      cut += " m driven";
    }
    text += cut + "\n";
  }
  return text;
}

}  // namespace

ModeSummary SummarizeMode(MapMode mode, const AggregateMetrics& aggregate) {
  return {mode, aggregate.runs, aggregate.successes, aggregate};
}

std::string SummaryText(const Scenario& scenario, const std::vector<ModeSummary>& modes,
                        const TeachSpeed& teach, const std::filesystem::path& out,
                        double wall_time_s) {
  std::string text = ScenarioLine(scenario) + MainTable(modes) + SocialLines(modes) +
                     LocalizerLines(modes) + SwitchingLines(modes);
  text +=
      "(m; track = distance to the taught trajectory, loc = localization error in the map, repeat "
      "= "
      "repeatability, coll_ped = pedestrian collisions (of them, the robot driving into the "
      "pedestrian), rtf = real-time factor per core)\n";
  if (teach.cpu_time_s > 0.0) {
    text += "teaching drive: " + Cell(teach.duration_s, "%.0f") + " s simulated in " +
            Cell(teach.cpu_time_s, "%.1f") + " s of CPU for " + std::to_string(modes.size()) +
            (modes.size() == 1 ? " mode" : " modes") + " (" +
            Cell(teach.duration_s / teach.cpu_time_s, "%.0f") + "x real time)\n";
  }
  text += "results in " + out.string() + " (" + Cell(wall_time_s, "%.1f") + " s)\n";
  return text;
}

}  // namespace retrace::bench
