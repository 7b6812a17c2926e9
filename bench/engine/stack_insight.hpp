#pragma once
// What the harness may look at inside a stack built on retrace's localizer and map server
// (bench/stack/navigation_stack.hpp, NavigationStack::insight): the measurement update of the
// last scan (its dynamic-point rejection is scored against the simulator's labels), the belief
// and the maps (the video and the scan snapshot draw them). Optional: a stack without it is
// scored on its output alone.

#include "bench/stack/navigation_stack.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"

namespace retrace::bench {

class StackInsight {
 public:
  virtual ~StackInsight() = default;
  /// The update of the last scan (nullptr before the first; `ran` false: gated).
  virtual const nav::LocalizerUpdate* last_update() const = 0;
  virtual const nav::Localizer& localizer() const = 0;
  virtual const nav::MapServer& server() const = 0;
};

}  // namespace retrace::bench
