#include "bench/engine/playback.hpp"

#include <memory>

#include "bench/engine/playback_episode.hpp"
#include "bench/engine/stack_registry.hpp"
#include "core/rng.hpp"

namespace retrace::bench {

core::Rng PlaybackRng(const ScenarioConfig& config, int run) {
  return core::Rng(config.seed).Split("playback").Split(static_cast<std::uint64_t>(run));
}

RunTrace RunPlayback(const Scenario& scenario, const nav::TeachBundle& bundle,
                     const TeachTrace& teach, int run, double timeout_s, const ProgressFn& progress,
                     PlaybackObserver* observer, SensorTap* tap) {
  const std::unique_ptr<NavigationStack> stack = MakeStack(scenario, bundle, run);
  PlaybackEpisode episode(scenario, bundle, teach, run, timeout_s, *stack, progress, observer, tap);
  do {
    episode.Sense();
  } while (!episode.Act());
  return episode.Finish();
}

}  // namespace retrace::bench
