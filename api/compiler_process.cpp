#include "api/compiler_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <algorithm>
#include <mutex>
#include <thread>

extern char** environ;

namespace mbfe {

namespace {

constexpr int kEndingSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr int kNumEndingSignals = sizeof kEndingSignals / sizeof kEndingSignals[0];
constexpr int kPollMilliseconds = 50;  // how soon a recorded signal is noticed
constexpr auto kTermGrace = std::chrono::seconds(1);  // SIGTERM to SIGKILL: the compiler stops at once on SIGTERM

volatile std::sig_atomic_t g_recorded_signal = 0;

extern "C" void record_signal(int signal) {
  if (!g_recorded_signal) g_recorded_signal = signal;
}

// Who defers signals now, and the dispositions to restore after the last.
struct Deferral {
  std::mutex mutex;
  int users = 0;
  struct sigaction previous[kNumEndingSignals];
  bool replaced[kNumEndingSignals] = {};
};

Deferral& deferral() {
  static Deferral d;
  return d;
}

void close_fd(int fd) {
  if (fd >= 0) ::close(fd);
}

// Sends SIGTERM to the group led by `leader` (our child), waits for the
// whole group to go, SIGKILL after kTermGrace; reaps the leader.
int end_group(pid_t leader) {
  ::kill(-leader, SIGTERM);
  int raw = 0;
  bool reaped = false;
  const auto deadline = std::chrono::steady_clock::now() + kTermGrace;
  for (;;) {
    if (!reaped && ::waitpid(leader, &raw, WNOHANG) == leader) reaped = true;
    if (reaped && ::kill(-leader, 0) != 0 && errno == ESRCH) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-leader, SIGKILL);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  while (!reaped) {
    const pid_t r = ::waitpid(leader, &raw, 0);
    if (r == leader || (r < 0 && errno != EINTR)) reaped = true;
  }
  return raw;
}

const char* signal_name(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : signal == SIGHUP ? "SIGHUP" : "a signal";
}

int decode_status(int raw) {
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
  return 128;
}

}  // namespace

DeferredSignals::DeferredSignals() {
  Deferral& d = deferral();
  std::lock_guard<std::mutex> lock(d.mutex);
  if (d.users++ > 0) return;
  g_recorded_signal = 0;
  for (int i = 0; i < kNumEndingSignals; ++i) {
    ::sigaction(kEndingSignals[i], nullptr, &d.previous[i]);
    // An ignored signal stays ignored (nohup, a background job's SIGINT).
    d.replaced[i] = (d.previous[i].sa_flags & SA_SIGINFO) || d.previous[i].sa_handler != SIG_IGN;
    if (!d.replaced[i]) continue;
    struct sigaction record {};
    record.sa_handler = record_signal;
    sigemptyset(&record.sa_mask);
    ::sigaction(kEndingSignals[i], &record, nullptr);
  }
}

DeferredSignals::~DeferredSignals() {
  if (finished_) return;
  finished_ = true;
  if (const int signal = release()) ::raise(signal);
}

int DeferredSignals::caught() const { return g_recorded_signal; }

int DeferredSignals::release() noexcept {
  Deferral& d = deferral();
  std::lock_guard<std::mutex> lock(d.mutex);
  if (--d.users > 0) return 0;
  for (int i = 0; i < kNumEndingSignals; ++i)
    if (d.replaced[i]) ::sigaction(kEndingSignals[i], &d.previous[i], nullptr);
  const int signal = g_recorded_signal;
  g_recorded_signal = 0;
  return signal;
}

void DeferredSignals::finish() {
  if (finished_) return;
  finished_ = true;
  const int recorded = g_recorded_signal;
  const int to_raise = release();
  if (to_raise) ::raise(to_raise);  // its usual effect: by default the process ends here
  if (to_raise || recorded)
    throw CompileInterrupted(std::string("interrupted by ") + signal_name(to_raise ? to_raise : recorded) +
                             " while compiling a solver");
}

CompilerRun run_compiler(const std::string& command, std::size_t max_output, const DeferredSignals& signals) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot start the compiler: pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults, none;
  sigemptyset(&defaults);
  for (int s : kEndingSignals) sigaddset(&defaults, s);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setpgroup(&attr, 0);  // a group of its own: ended as one, and the terminal's ^C is ours to pass on
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  std::string sh = "sh", dash_c = "-c", text = command;
  char* argv[] = {sh.data(), dash_c.data(), text.data(), nullptr};
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, "/bin/sh", &actions, &attr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  close_fd(pipe_fds[1]);
  if (rc != 0) {
    close_fd(pipe_fds[0]);
    throw std::runtime_error("cannot start the compiler (" + command + "): " + std::strerror(rc));
  }

  CompilerRun run;
  bool open = true;
  while (open && !signals.caught()) {
    pollfd p{pipe_fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, kPollMilliseconds);
    if (ready <= 0) continue;  // timeout, or EINTR from a recorded signal
    char buffer[4096];
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      open = false;
      break;
    }
    if (run.output.size() < max_output)
      run.output.append(buffer, std::min(static_cast<std::size_t>(n), max_output - run.output.size()));
  }
  close_fd(pipe_fds[0]);
  // Output closed: the compiler is exiting; wait for it, still watching for signals.
  int raw = 0;
  for (;;) {
    if (signals.caught()) {
      raw = end_group(pid);
      run.interrupted = true;
      break;
    }
    const pid_t r = ::waitpid(pid, &raw, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw std::runtime_error(std::string("waiting for the compiler: ") + std::strerror(errno));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  run.status = decode_status(raw);
  return run;
}

}  // namespace mbfe
