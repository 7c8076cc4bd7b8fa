// The progress of a long run on stderr: on a terminal one refreshed line with
// the simulated time, the end time and the wall time left; elsewhere (a log
// file, a batch job) a plain line every 30 s. Nothing for runs that end within
// a few seconds, nothing with --quiet.
#pragma once

#include <chrono>
#include <cstdint>

namespace mbfe::tool {

class ProgressLine {
 public:
  /// `enabled`: false for --quiet. The run goes from t = 0 to t_end (s) in
  /// steps of equal length, so the share done is t / t_end (no step count
  /// is needed, which may be beyond what an int64 holds before the run
  /// refuses it).
  ProgressLine(bool enabled, double t_end);
  /// After step `steps`, at simulated time t (s).
  void update(double t, std::int64_t steps);
  /// Clears the refreshed line, if one was shown.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_, terminal_;
  double t_end_;
  Clock::time_point start_, last_;
  bool shown_ = false;
};

}  // namespace mbfe::tool
