#include "bench/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace retrace::bench {

ProgressLine::ProgressLine() : enabled_(isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() { Clear(); }

void ProgressLine::Phase(const std::string& name, int total) {
  std::lock_guard lock(mutex_);
  phase_ = name;
  countdown_ = false;
  total_ = total;
  done_ = 0;
  sim_time_ = 0.0;
  start_ = std::chrono::steady_clock::now();
  Draw(true);
}

void ProgressLine::CountdownPhase(const std::string& name, int total, int done) {
  std::lock_guard lock(mutex_);
  phase_ = name;
  countdown_ = true;
  total_ = total;
  done_ = done;
  done_before_ = done;
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

void ProgressLine::Warning(const std::string& text) {
  std::lock_guard lock(mutex_);
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
  std::fprintf(stderr, "retrace: warning: %s\n", text.c_str());
  std::fflush(stderr);
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
  if (countdown_) {
    // The rate of this session only: resumed units took no time here.
    const int done_here = done_ - done_before_;
    const std::string left = done_here > 0
                                 ? FormatDuration(wall / done_here * (total_ - done_)) + " left"
                                 : "estimating the time left";
    const std::string bar = ProgressBar(done_, total_, 24);
    std::fprintf(stderr, "\r\033[K%s %s %d/%d done, %s", phase_.c_str(), bar.c_str(), done_, total_,
                 left.c_str());
    std::fflush(stderr);
    drawn_ = true;
    return;
  }
  std::fprintf(stderr, "\r\033[K%s: %d/%d done, %.0f s simulated, %.0fx real time", phase_.c_str(),
               done_, total_, sim_time_, wall > 0.0 ? sim_time_ / wall : 0.0);
  std::fflush(stderr);
  drawn_ = true;
}

std::string ProgressBar(int done, int total, int width) {
  const int filled = total > 0 ? std::clamp(done, 0, total) * width / total : 0;
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "[" + std::string(...).
  std::string bar = "[";
  bar.append(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(width - filled), '-');
  bar += ']';
  return bar;
}

}  // namespace retrace::bench
