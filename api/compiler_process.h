// Running the compiler of a solver so that it ends with mbfe: a command in a
// process group of its own, its output captured, and SIGINT, SIGTERM and
// SIGHUP to mbfe held off while a build runs, so that the compiler's whole
// group is ended and the build folder removed before the signal takes its
// usual effect.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace mbfe {

/// A build ended by SIGINT, SIGTERM or SIGHUP whose previous handler
/// returned (it only recorded the signal, as Python's does), or that another
/// thread's build will raise: the caller unwinds, the program decides what
/// the signal means.
class CompileInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// While at least one DeferredSignals lives (in any thread), SIGINT, SIGTERM
/// and SIGHUP, unless ignored, are recorded instead of acted on. The last one
/// to finish restores the previous dispositions and raises a recorded signal
/// again, so that it has its usual effect (by default the process dies of
/// it); until then the builds clean up.
class DeferredSignals {
 public:
  DeferredSignals();
  /// finish() if not called, except that it never throws.
  ~DeferredSignals();
  DeferredSignals(const DeferredSignals&) = delete;
  DeferredSignals& operator=(const DeferredSignals&) = delete;

  /// The signal recorded so far, 0 if none.
  int caught() const;

  /// Ends this deferral. @throws CompileInterrupted when a signal was
  /// recorded and the process is still alive afterwards (the raised signal
  /// returned, or another build will raise it).
  void finish();

 private:
  int release() noexcept;  // the signal to raise (the last one out), else 0
  bool finished_ = false;
};

struct CompilerRun {
  int status = 0;            // exit status; 128 + n when the command died of signal n
  std::string output;        // stdout and stderr interleaved, the first max_output bytes
  bool interrupted = false;  // a deferred signal came: the process group was ended
};

/// Runs `command` with /bin/sh -c in a new process group, stdin from
/// /dev/null. When `signals` records a signal meanwhile, the group is sent
/// SIGTERM (SIGKILL after a second if some of it lives on) and the run
/// returns, interrupted. @throws std::runtime_error when it cannot start.
CompilerRun run_compiler(const std::string& command, std::size_t max_output, const DeferredSignals& signals);

}  // namespace mbfe
