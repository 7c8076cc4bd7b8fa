// Ctrl-C, SIGTERM and SIGHUP during a run: the handlers only note the signal;
// the run's monitor sees it before the next step and stops there, so the
// results keep whole rows and the record beside them says "interrupted"
// (exit status 3). Installed for the run's duration, the earlier handlers
// restored afterwards.
#pragma once

#include <csignal>

namespace mbfe::tool {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// A signal has come since the guard was made.
  static bool interrupted();
  /// Which (SIGINT, SIGTERM, SIGHUP), 0 for none.
  static int signal_number();

 private:
  struct sigaction previous_[3];
};

}  // namespace mbfe::tool
