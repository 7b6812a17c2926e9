#include "bench/metrics/metrics_json.hpp"

#include <array>
#include <string>

#include "io/json_writer.hpp"
#include "nav/scan_matcher.hpp"

namespace retrace::bench {
namespace {

nlohmann::json ToJson(const CollisionStats& c) {
  return {{"static_incidents", c.static_incidents},
          {"pedestrian_incidents", c.pedestrian_incidents},
          {"pedestrian_incidents_robot_driving", c.pedestrian_incidents_robot_driving},
          {"static_events", c.static_events},
          {"pedestrian_events", c.pedestrian_events},
          {"min_clearance_m", io::JsonNumber(c.min_clearance_m)},
          {"min_pedestrian_gap_m", io::JsonNumber(c.min_pedestrian_gap_m)}};
}

nlohmann::json ToJson(const DynamicPointStats& d) {
  return {{"beams_tested", d.beams_tested},
          {"beams_rejected", d.beams_rejected},
          {"true_positive", d.true_positive},
          {"false_positive", d.false_positive},
          {"false_negative", d.false_negative},
          {"rejected_fraction", io::JsonNumber(d.rejected_fraction)},
          {"precision", io::JsonNumber(d.precision)},
          {"recall", io::JsonNumber(d.recall)}};
}

nlohmann::json ToJson(const CpuStats& c) {
  return {{"localizer_updates", c.localizer_updates},
          {"localizer_update_mean_ms", io::JsonNumber(c.localizer_update_mean_ms)},
          {"localizer_update_max_ms", io::JsonNumber(c.localizer_update_max_ms)},
          {"sim_time_s", io::JsonNumber(c.sim_time_s)},
          {"cpu_time_s", io::JsonNumber(c.cpu_time_s)},
          {"real_time_factor", io::JsonNumber(c.real_time_factor)}};
}

nlohmann::json ToJson(const CrowdReaction& c) {
  return {{"encounters", c.encounters},
          {"passed", c.passed},
          {"yielded", c.yielded},
          {"blocked", c.blocked},
          {"standing", c.standing},
          {"wait_time_s", io::JsonNumber(c.wait_time_s)},
          {"max_wait_s", io::JsonNumber(c.max_wait_s)}};
}

// The behaviours met (people > 0), by name.
nlohmann::json BehavioursJson(const SocialStats& s) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [behaviour, name] : core::EnumTraits<sim::RobotBehaviour>::kNames) {
    const BehaviourSocial& b = s.by_behaviour[static_cast<std::size_t>(behaviour)];
    if (b.people == 0 && b.runs_stopped == 0) continue;
    out[std::string(name)] = {{"people", b.people},
                              {"min_gap_m", io::JsonNumber(b.min_gap_m)},
                              {"intimate_time_s", io::JsonNumber(b.intimate_time_s)},
                              {"personal_time_s", io::JsonNumber(b.personal_time_s)},
                              {"crowd", ToJson(b.crowd)},
                              {"runs_stopped", b.runs_stopped}};
  }
  return out;
}

nlohmann::json ToJson(const SocialStats& s) {
  const CrowdReaction& c = s.crowd;
  nlohmann::json j = {{"intimate_time_s", io::JsonNumber(s.intimate_time_s)},
                      {"personal_time_s", io::JsonNumber(s.personal_time_s)},
                      {"min_ttc_s", io::JsonNumber(s.min_ttc_s)},
                      {"path_efficiency", io::JsonNumber(s.path_efficiency)},
                      {"time_efficiency", io::JsonNumber(s.time_efficiency)},
                      {"jerk_m_s3", ToJson(s.jerk_m_s3)},
                      {"crowd", ToJson(c)}};
  // Only where someone behaved otherwise than `regular` toward the robot: a crowd of regular
  // people keeps the files it had.
  bool others = s.stopped_by.has_value();
  for (std::size_t b = 1; b < s.by_behaviour.size(); ++b) others |= s.by_behaviour[b].people > 0;
  if (others) j["by_behaviour"] = BehavioursJson(s);
  // A failed run that someone reacting to the robot stood in the way of.
  if (s.stopped_by) j["stopped_by"] = std::string(core::EnumName(*s.stopped_by));
  return j;
}

nlohmann::json ToJson(const MapQualityStats& q) {
  nlohmann::json per_map = nlohmann::json::array();
  for (const MapQuality& m : q.maps) {
    per_map.push_back(
        {{"distortion_m", m.distortion_m},
         {"agreement", m.occupied_cells > 0 ? io::JsonNumber(static_cast<double>(m.agreeing_cells) /
                                                             m.occupied_cells)
                                            : nlohmann::json(nullptr)},
         {"occupied_cells", m.occupied_cells}});
  }
  return {{"distortion_m", {{"rms", q.distortion_rms_m}, {"max", q.distortion_max_m}}},
          {"agreement", io::JsonNumber(q.agreement)},
          {"per_map", std::move(per_map)}};
}

// Keyframe matches of the scan_matched mode by verdict, and how many fell back to odometry
// (refused: every verdict but matched; the map's first keyframe is always "empty_map").
nlohmann::json MatchCountsJson(const std::array<int, 5>& counts) {
  nlohmann::json j = nlohmann::json::object();
  int total = 0;
  for (const auto& [verdict, name] : core::EnumTraits<nav::MatchVerdict>::kNames) {
    const int n = counts[static_cast<std::size_t>(verdict)];
    j[std::string(name)] = n;
    total += n;
  }
  j["keyframes"] = total;
  j["refused"] = total - counts[static_cast<std::size_t>(nav::MatchVerdict::kMatched)];
  return j;
}

nlohmann::json PooledAndRunMean(const Summary& pooled, const Summary& run_mean) {
  return {{"pooled", ToJson(pooled)}, {"run_mean", ToJson(run_mean)}};
}

}  // namespace

nlohmann::json ToJson(const LocalizerHealth& h) {
  return {{"lost_time_s", io::JsonNumber(h.lost_time_s)},
          {"lost_spells", h.lost_spells},
          {"reacquisitions", h.reacquisitions},
          {"max_jump_m", io::JsonNumber(h.max_jump_m)},
          {"max_jump_time_s", io::JsonNumber(h.max_jump_time_s)},
          {"max_error_increase_m", io::JsonNumber(h.max_error_increase_m)},
          {"max_error_increase_time_s", io::JsonNumber(h.max_error_increase_time_s)},
          {"reacquisitions_closer", h.reacquisitions_closer},
          {"reacquisitions_wrong", h.reacquisitions_wrong},
          {"off_map_time_s", io::JsonNumber(h.off_map_time_s)},
          {"silent_failure_time_s", io::JsonNumber(h.silent_failure_time_s)},
          {"longest_silent_failure_s", io::JsonNumber(h.longest_silent_failure_s)},
          {"false_alarm_time_s", io::JsonNumber(h.false_alarm_time_s)},
          {"wrong_switches", h.wrong_switches}};
}

nlohmann::json ToJson(const Summary& s) {
  return {{"mean", io::JsonNumber(s.mean)},
          {"rms", io::JsonNumber(s.rms)},
          {"p95", io::JsonNumber(s.p95)},
          {"max", io::JsonNumber(s.max)},
          {"count", s.count}};
}

nlohmann::json ToJson(const RunMetrics& m) {
  nlohmann::json switches = nlohmann::json::array();
  for (const SwitchError& e : m.switches) {
    switches.push_back({{"time_s", io::JsonNumber(e.time_s)},
                        {"from", e.from},
                        {"to", e.to},
                        {"error_m", io::JsonNumber(e.error_m)},
                        {"error_rad", io::JsonNumber(e.error_rad)}});
  }
  return {{"run", m.run},
          {"seed", m.seed},
          {"outcome", std::string(core::EnumName(m.outcome))},
          {"success", m.success},
          {"samples", m.samples},
          {"time_s", io::JsonNumber(m.time_s)},
          {"path_length_m", io::JsonNumber(m.path_length_m)},
          {"progress_m", io::JsonNumber(m.progress_m)},
          {"tracking_error_m", ToJson(m.tracking_error_m)},
          {"localization_error_m", ToJson(m.localization_error_m)},
          {"localization_error_rad", ToJson(m.localization_error_rad)},
          {"lost_fraction", io::JsonNumber(m.lost_fraction)},
          {"localizer", ToJson(m.localizer)},
          {"collisions", ToJson(m.collisions)},
          {"switch_error",
           {{"count", m.switches.size()},
            {"max_m", io::JsonNumber(m.switch_error_max_m)},
            {"max_rad", io::JsonNumber(m.switch_error_max_rad)},
            {"switches", std::move(switches)}}},
          {"dynamic_points", ToJson(m.dynamic_points)},
          {"social", ToJson(m.social)},
          {"cpu", ToJson(m.cpu)}};
}

nlohmann::json ToJson(const AggregateMetrics& a) {
  nlohmann::json outcomes = nlohmann::json::object();
  for (const auto& [outcome, name] : core::EnumTraits<Outcome>::kNames) {
    outcomes[std::string(name)] = a.outcome_counts[static_cast<std::size_t>(outcome)];
  }
  const Repeatability& r = a.repeatability;
  nlohmann::json collisions = ToJson(a.collisions);
  collisions["runs_with_collision"] = a.runs_with_collision;
  return {{"runs", a.runs},
          {"successes", a.successes},
          {"success_rate", io::JsonNumber(a.success_rate)},
          {"outcomes", std::move(outcomes)},
          {"taught_path_length_m", io::JsonNumber(a.taught_path_length_m)},
          {"mean_time_s", io::JsonNumber(a.mean_time_s)},
          {"mean_path_length_m", io::JsonNumber(a.mean_path_length_m)},
          {"mean_progress_m", io::JsonNumber(a.mean_progress_m)},
          {"tracking_error_m",
           PooledAndRunMean(a.tracking_error_m_pooled, a.tracking_error_m_run_mean)},
          {"localization_error_m",
           PooledAndRunMean(a.localization_error_m_pooled, a.localization_error_m_run_mean)},
          {"localization_error_rad",
           PooledAndRunMean(a.localization_error_rad_pooled, a.localization_error_rad_run_mean)},
          {"lost_fraction",
           {{"pooled", io::JsonNumber(a.lost_fraction_pooled)},
            {"run_mean", io::JsonNumber(a.lost_fraction_run_mean)}}},
          {"localizer", ToJson(a.localizer)},
          {"repeatability_m", io::JsonNumber(r.repeatability_m)},
          {"repeatability_max_spread_m", io::JsonNumber(r.max_spread_m)},
          {"repeatability_stations_used", r.stations_used},
          {"collisions", std::move(collisions)},
          {"switch_error",
           {{"count", a.switch_error.count},
            {"mean_m", io::JsonNumber(a.switch_error.mean_m)},
            {"max_m", io::JsonNumber(a.switch_error.max_m)},
            {"mean_rad", io::JsonNumber(a.switch_error.mean_rad)},
            {"max_rad", io::JsonNumber(a.switch_error.max_rad)}}},
          {"dynamic_points", ToJson(a.dynamic_points)},
          {"maps", a.map_quality.maps.size()},
          {"map_quality", ToJson(a.map_quality)},
          {"switching",
           {{"minimum_maps", a.switching.minimum},
            {"revisiting_maps", a.switching.revisiting},
            {"switch_travel_m", a.switching.switch_travel_m},
            {"reasons", a.switching.reasons},
            {"switches_by_reason",
             {{"operator", a.switching.reason_counts.operator_points},
              {"auto", a.switching.reason_counts.auto_points},
              {"revisit", a.switching.reason_counts.revisit},
              {"drift_budget", a.switching.reason_counts.drift_budget}}}}},
          {"scan_matching", MatchCountsJson(a.match_counts)},
          {"social", ToJson(a.social)},
          {"cpu", ToJson(a.cpu)}};
}

}  // namespace retrace::bench
