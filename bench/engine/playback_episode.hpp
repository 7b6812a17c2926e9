#pragma once
// One playback run as an object that is stepped (docs/DESIGN.md §6): Sense steps the world to
// the next control tick and hands every odometry increment and scan to the navigation stack on
// the way; Act asks the stack for its answer at that tick, drives the robot with it (or with the
// operator's command while one has taken it over), records, fires scripted events and checks
// the end. RunPlayback (playback.hpp) is `do Sense(); while (!Act());`; a caller that steps a
// stack itself (the Python module) calls the same two, so its runs are measured exactly as
// `retrace run`'s.

#include <memory>
#include <optional>

#include "bench/engine/playback_observer.hpp"
#include "bench/engine/progress.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/sensor_tap.hpp"
#include "bench/engine/trace.hpp"
#include "bench/stack/navigation_stack.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

class PlaybackEpisode {
 public:
  /// Playback run `run` of `scenario` on `stack` (which must outlive the episode) along
  /// `bundle`'s taught paths, measured against `teach` (the teaching drive's ground truth and
  /// per-map references); both must outlive it too. `timeout_s` ends a run that has not reached
  /// the end of the route. Throws core::WorldError when the world refuses the start pose.
  PlaybackEpisode(const Scenario& scenario, const nav::TeachBundle& bundle,
                  const TeachTrace& teach, int run, double timeout_s, NavigationStack& stack,
                  const ProgressFn& progress = {}, PlaybackObserver* observer = nullptr,
                  SensorTap* tap = nullptr);
  ~PlaybackEpisode();
  PlaybackEpisode(const PlaybackEpisode&) = delete;
  PlaybackEpisode& operator=(const PlaybackEpisode&) = delete;

  /// Steps the world up to the next control tick with the last command; the stack gets each
  /// odometry increment and scan. Requires !done().
  void Sense();
  /// The control tick: the stack's answer (the operator's command while one drives), sent,
  /// recorded; scripted events; the end conditions. Returns done(). Requires a Sense() before.
  bool Act();
  bool done() const;
  /// s of simulated time since the run started.
  double time() const;
  /// The run's trace, once done(); the episode is spent afterwards.
  RunTrace Finish();
  /// The last control tick's sample (nullptr before the first Act, and after Finish).
  const PlaybackSample* last_sample() const;
  /// The collisions so far.
  std::size_t collisions() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace retrace::bench
