#include "tool/progress_line.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace mbfe::tool {

namespace {

// Looking at the clock costs ~20 ns: every this many steps only.
constexpr std::int64_t kCheckEvery = 256;
// A run shorter than this needs no progress.
constexpr double kQuietSeconds = 3.0;
// Refresh on a terminal, and a plain line elsewhere, at most this often (s).
constexpr double kTerminalRefresh = 0.5;
constexpr double kPlainEvery = 30.0;

}  // namespace

ProgressLine::ProgressLine(bool enabled, double t_end)
    : enabled_(enabled), terminal_(isatty(fileno(stderr)) != 0), t_end_(t_end), start_(Clock::now()), last_(start_) {}

void ProgressLine::update(double t, std::int64_t steps) {
  if (!enabled_ || steps % kCheckEvery != 0 || steps == 0 || !(t > 0.0)) return;
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (elapsed < kQuietSeconds || since < (terminal_ ? kTerminalRefresh : kPlainEvery)) return;
  last_ = now;
  const double left = elapsed * std::max(t_end_ - t, 0.0) / t;
  const double percent = 100.0 * std::min(t / t_end_, 1.0);
  if (terminal_) {
    std::fprintf(stderr, "\r  t = %.4g s of %.4g s (%.0f %%), about %.0f s left   ", t, t_end_, percent, left);
    shown_ = true;
  } else {
    std::fprintf(stderr, "mbfe: t = %.4g s of %.4g s (%.0f %%), about %.0f s left\n", t, t_end_, percent, left);
  }
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (!shown_) return;
  std::fprintf(stderr, "\r%70s\r", "");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace mbfe::tool
