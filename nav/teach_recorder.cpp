#include "nav/teach_recorder.hpp"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "core/check.hpp"
#include "nav/scan_constraint.hpp"

namespace retrace::nav {
namespace {

// m of travel between the places compared when choosing where to switch, as for
// `route.switch_points: auto` (bench/engine/switch_visibility.cpp).
constexpr double kPlaceSpacing = 0.5;

}  // namespace

TeachRecorder::TeachRecorder(const MapperConfig& config, const RobotGeometry& robot,
                             const std::optional<ScanMatcherConfig>& matcher,
                             const std::optional<OnlineSwitchingConfig>& online)
    : config_(config), robot_(robot), mapper_(config, robot) {
  if (matcher) matcher_.emplace(*matcher, robot);
  if (online) detector_.emplace(*online);
}

void TeachRecorder::OnPose(const core::Pose2& X_OR) {
  RETRACE_CHECK(!finished_);
  if (!detector_) {
    ApplyPose(X_OR);
    return;
  }
  X_OR_latest_ = X_OR;
  const bool revisit = detector_->OnPose(X_OR);
  held_.push_back({X_OR, detector_->travelled()});
  if (revisit) {
    SwitchOnline(SwitchReason::kRevisit);
  } else if (detector_->DriftBudgetReached()) {
    SwitchOnline(SwitchReason::kDriftBudget);
  }
  // Hold back enough for the next switch to choose its place within the window.
  const double hold = detector_->config().window + 2.0 * detector_->step();
  BuildHeldUpTo(detector_->travelled() - hold);
}

bool TeachRecorder::OnScan(const core::LaserScan& scan) {
  RETRACE_CHECK(!finished_);
  if (!detector_) return ApplyScan(scan);
  if (!X_OR_latest_ || X_OR_latest_ == X_OR_last_scan_) return false;
  X_OR_last_scan_ = X_OR_latest_;
  held_.push_back({scan, detector_->travelled()});
  return false;
}

void TeachRecorder::ApplyPose(const core::Pose2& X_OR) {
  X_OR_ = X_OR;
  if (!X_OM_) X_OM_ = X_OR;    // the map starts here
  if (!X_OK_) X_OK_ = *X_OM_;  // ... at the identity, its first anchor
  // Exactly the identity at the map's origin (inverse(X) * X may be off by rounding).
  if (matcher_) {
    mapper_.SetPose(X_OR == *X_OK_ ? X_MK_ : X_MK_ * (X_OK_->Inverse() * X_OR));
  } else {
    mapper_.SetPose(X_OR == *X_OM_ ? core::Pose2::Identity() : X_OM_->Inverse() * X_OR);
  }
  recorded_.push_back({static_cast<std::uint32_t>(closed_.size()), mapper_.pose()});
}

bool TeachRecorder::ApplyScan(const core::LaserScan& scan) {
  if (!X_OR_) return false;
  if (!matcher_) return mapper_.OnScan(scan);
  if (!mapper_.KeyframeDue()) return false;
  const ScanMatch match = matcher_->Match(scan, mapper_.pose());
  ++match_counts_[static_cast<std::size_t>(match.verdict)];
  mapper_.SetPose(match.X_MR);
  const bool integrated = mapper_.OnScan(scan);
  matcher_->AddScan(scan, mapper_.pose());
  X_MK_ = mapper_.pose();
  X_OK_ = X_OR_;
  return integrated;
}

void TeachRecorder::CloseMap() {
  RETRACE_CHECK(!finished_);
  RETRACE_CHECK(!detector_);  // online switching closes its maps itself
  StartNextMap();
}

void TeachRecorder::StartNextMap() {
  PartialMap map;
  map.X_MS = mapper_.pose();  // identity if no pose has arrived yet
  // The taught path runs from the map's origin, where playback enters the map, to exactly the
  // switch pose, where playback stops to switch maps; keyframes in between.
  std::vector<core::Pose2> poses = mapper_.path().poses();
  if (poses.empty() || poses.front() != core::Pose2::Identity()) {
    poses.insert(poses.begin(), core::Pose2::Identity());
  }
  if (poses.back() != map.X_MS) poses.push_back(map.X_MS);
  map.path = core::Path(std::move(poses));
  map.grid = mapper_.grid();
  closed_.push_back(std::move(map));

  mapper_ = Mapper(config_, robot_);
  X_OM_ = X_OR_;  // map k+1 starts at the switch; if no pose is known yet, at the first one
  X_MK_ = core::Pose2::Identity();
  X_OK_ = X_OM_;
  if (matcher_) matcher_->Clear();
}

void TeachRecorder::SwitchOnline(SwitchReason reason) {
  // The revisit (or the end of the drift budget) is at the latest pose; the map must end at
  // least one step before it, and no earlier than `window` before that, nor before the map has
  // begun. A drift-budget switch thus ends the map within `window` before its budget runs out.
  const double latest = detector_->travelled() - detector_->step();
  // A revisit's map is at least as long as the loop the drift rule allows (MinMapLength).
  const double shortest =
      reason == SwitchReason::kRevisit ? detector_->config().MinMapLength() : 0.0;
  const double earliest = std::max({latest - detector_->config().window,
                                    map_start_travelled_ + kPlaceSpacing,
                                    std::min(map_start_travelled_ + shortest, latest)});
  // The held scans one place spacing apart, nearest first, so that of equal places the one
  // closest to the revisit wins (as for `auto` points).
  std::size_t chosen = held_.size();
  double best = -1.0;
  double last_place = std::numeric_limits<double>::infinity();
  for (std::size_t i = held_.size(); i-- > 0;) {
    const Held& h = held_[i];
    if (h.travelled > latest) continue;
    if (h.travelled < earliest) break;
    const auto* scan = std::get_if<core::LaserScan>(&h.event);
    if (scan == nullptr || last_place - h.travelled < kPlaceSpacing) continue;
    last_place = h.travelled;
    const double c = ScanConstraint(*scan, robot_);
    if (c > best) {
      best = c;
      chosen = i;
    }
  }
  if (chosen == held_.size()) {
    // No scan held in the window (a log without scans there): switch at the last pose before
    // the revisit.
    for (std::size_t i = held_.size(); i-- > 0;) {
      if (held_[i].travelled < earliest) break;
      if (held_[i].travelled <= latest && std::holds_alternative<core::Pose2>(held_[i].event)) {
        chosen = i + 1;
        break;
      }
    }
    if (chosen == held_.size()) return;  // nothing held that early: switch at the next chance
    best = 0.0;
  }
  // Everything before the chosen scan goes into the current map; the map ends at the pose the
  // scan was taken at, and the scan is the next map's first keyframe.
  const double travelled = held_[chosen].travelled;
  for (std::size_t i = 0; i < chosen; ++i) BuildFirstHeld();
  StartNextMap();
  detector_->StartMap(travelled);
  map_start_travelled_ = travelled;
  switches_.push_back({travelled, best, reason});
}

void TeachRecorder::BuildFirstHeld() {
  Held& h = held_.front();
  if (const auto* X_OR = std::get_if<core::Pose2>(&h.event)) {
    ApplyPose(*X_OR);
  } else {
    ApplyScan(std::get<core::LaserScan>(h.event));
  }
  held_.pop_front();
}

void TeachRecorder::BuildHeldUpTo(double travelled) {
  while (!held_.empty() && held_.front().travelled < travelled) BuildFirstHeld();
}

TeachBundle TeachRecorder::Finish() {
  RETRACE_CHECK(!finished_);
  if (detector_) BuildHeldUpTo(std::numeric_limits<double>::infinity());
  StartNextMap();
  finished_ = true;
  TeachBundle bundle;
  bundle.maps = std::move(closed_);
  closed_.clear();
  return bundle;
}

}  // namespace retrace::nav
