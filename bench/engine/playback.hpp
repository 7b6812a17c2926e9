#pragma once
// One playback run: the robot drives the taught route by itself with the navigation stack in
// the loop. The tick loop (PlaybackEpisode's Sense and Act, playback_episode.cpp) is the one
// place where the simulated world and the navigation stack meet; read it top to bottom.

#include <cstdint>
#include <memory>

#include "bench/stack/navigation_stack.hpp"
#include "bench/engine/playback_observer.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

/// The seed of playback run `run`: the same in every map mode, so that the modes' runs are
/// paired (same start offset, same pedestrians, same sensor noise draws).
core::Rng PlaybackRng(const ScenarioConfig& config, int run);

/// Runs playback run `run` on the maps and paths of `bundle`, measuring against `teach` (the
/// teaching drive's ground truth and the bundle's references). `timeout_s` ends a run that has
/// not reached the end of the last path. Returns everything the metrics need; expected outcomes
/// (timeout, lost, collision) are in RunTrace::outcome, not exceptions. Throws core::WorldError
/// only when the world refuses the start pose or a scripted event. An `observer` sees every
/// control tick and cannot change the run.
RunTrace RunPlayback(const Scenario& scenario, const nav::TeachBundle& bundle,
                     const TeachTrace& teach, int run, double timeout_s,
                     const ProgressFn& progress = {}, PlaybackObserver* observer = nullptr,
                     SensorTap* tap = nullptr);

}  // namespace retrace::bench
