#include "nav/teach_recorder.hpp"

#include <utility>
#include <vector>

#include "core/check.hpp"

namespace retrace::nav {

TeachRecorder::TeachRecorder(const MapperConfig& config, const RobotGeometry& robot,
                             const std::optional<ScanMatcherConfig>& matcher)
    : config_(config), robot_(robot), mapper_(config, robot) {
  if (matcher) matcher_.emplace(*matcher, robot);
}

void TeachRecorder::OnPose(const core::Pose2& X_OR) {
  RETRACE_CHECK(!finished_);
  X_OR_ = X_OR;
  if (!X_OM_) X_OM_ = X_OR;    // the map starts here
  if (!X_OK_) X_OK_ = *X_OM_;  // ... at the identity, its first anchor
  // Exactly the identity at the map's origin (inverse(X) * X may be off by rounding).
  if (matcher_) {
    mapper_.SetPose(X_OR == *X_OK_ ? X_MK_ : X_MK_ * (X_OK_->Inverse() * X_OR));
  } else {
    mapper_.SetPose(X_OR == *X_OM_ ? core::Pose2::Identity() : X_OM_->Inverse() * X_OR);
  }
}

bool TeachRecorder::OnScan(const core::LaserScan& scan) {
  RETRACE_CHECK(!finished_);
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

TeachBundle TeachRecorder::Finish() {
  CloseMap();
  finished_ = true;
  TeachBundle bundle;
  bundle.maps = std::move(closed_);
  closed_.clear();
  return bundle;
}

}  // namespace retrace::nav
