#include "bench/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace retrace::bench {

ProgressLine::ProgressLine() : enabled_(isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() { Clear(); }

void ProgressLine::Phase(const std::string& name, int total) {
  std::lock_guard lock(mutex_);
  phase_ = name;
  total_ = total;
  done_ = 0;
  sim_time_ = 0.0;
  start_ = std::chrono::steady_clock::now();
  Draw(true);
}

void ProgressLine::AddSimTime(double seconds) {
  std::lock_guard lock(mutex_);
  sim_time_ += seconds;
  Draw(false);
}

void ProgressLine::UnitDone() {
  std::lock_guard lock(mutex_);
  ++done_;
  Draw(true);
}

void ProgressLine::Clear() {
  std::lock_guard lock(mutex_);
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
}

void ProgressLine::Draw(bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_draw_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r\033[K%s: %d/%d done, %.0f s simulated, %.0fx real time", phase_.c_str(), done_, total_,
               sim_time_, wall > 0.0 ? sim_time_ / wall : 0.0);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace retrace::bench
