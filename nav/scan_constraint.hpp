#pragma once
// How well one scan pins the robot's position down — the measure the paper's §3.1 asks for when
// it says to switch maps "at places with enough landmarks ahead", and the one the scan matcher
// uses to call a match degenerate (nav/scan_matcher.hpp): the smaller eigenvalue of Σ n nᵀ over
// the scan's end points (kept 0.1 m apart; n the unit normal of the surface through each end
// point and its neighbours along the scan), i.e. about the number of end points that constrain
// the weakest direction. A featureless corridor along its axis or an open field scores near 0.

#include "core/laser_scan.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::nav {

/// The constraint of one scan (see above); 0 for a scan without usable end points.
double ScanConstraint(const core::LaserScan& scan, const RobotGeometry& robot);

}  // namespace retrace::nav
