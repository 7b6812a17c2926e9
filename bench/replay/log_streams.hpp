#pragma once
// The streams a log command drives the navigation stack with (docs/DESIGN.md §10): the
// odometry, the robot's geometry and, to measure against, a reference trajectory — the log's
// own, one from a TUM file, or, with synthetic odometry, the log's odometry itself.
//
// Synthetic odometry: a corrected log (its poses already made consistent by SLAM) has no drift
// left, so partial maps built from it would be perfect. --synthetic-odometry takes the log's
// best trajectory as the reference and drives the simulator's wheel-odometry model
// (sim/odometry.hpp, seeded) along it, so the maps are distorted as on a real robot while every
// scan stays real.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/replay/log_config.hpp"
#include "io/tum.hpp"
#include "logs/sensor_log.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::bench {

struct LogStreams {
  std::vector<io::StampedPose> odometry;   ///< X_OR by stamp
  std::vector<io::StampedPose> reference;  ///< X_WR by stamp; empty: no reference
  std::string odometry_source;             ///< for people and manifests
  std::string reference_source;
  nav::RobotGeometry robot;  ///< the mount and range limits of the log's LiDAR
};

/// The streams of `index` (which must be usable, logs::RequireUsable): the reference from
/// `reference_file` (TUM, stamps on the log's clock) if given, else the log's own; with
/// `synthetic_odometry`, odometry drawn from that reference (or, without one, from the log's
/// odometry, which then becomes the reference) with `config.sim.odometry` and `config.seed`.
/// Throws core::IoError for an unreadable reference file or one that does not overlap the log's
/// odometry (without one, its scans) in time, and for a log without odometry
/// (LogIndex::odometry_missing) unless synthetic odometry is drawn from a reference: one line
/// saying what is missing and, where a reference can stand in, to add --synthetic-odometry.
LogStreams PrepareLogStreams(const logs::LogIndex& index, const LogConfig& config,
                             bool synthetic_odometry,
                             const std::optional<std::filesystem::path>& reference_file);

/// Odometry X_OR at the stamps of `truth`, starting at the identity, from the wheel-odometry
/// model driven along `truth` in steps of at most 2 cm and 1 degree.
std::vector<io::StampedPose> SyntheticOdometry(const std::vector<io::StampedPose>& truth,
                                               const sim::OdometryConfig& config, core::Rng rng);

/// The manifest fields every log command writes about the log and its streams, in order: log,
/// log_format, scan_topic, stamps (the log's, or nominal from --scan-rate), odometry, reference,
/// lidar_mount, from_s and to_s (the span used, s since the log's first scan).
std::vector<std::pair<std::string, std::string>> LogManifestFields(const logs::LogIndex& index,
                                                                   const LogStreams& streams,
                                                                   double from_s, double to_s);

}  // namespace retrace::bench
