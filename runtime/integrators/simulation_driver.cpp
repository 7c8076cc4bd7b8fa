#include "runtime/integrators/simulation_driver.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_sigint(int) { g_interrupted = 1; }

/// Installs the SIGINT handler for one run, restores the previous one after.
class SigintGuard {
 public:
  explicit SigintGuard(bool active) : active_(active) {
    g_interrupted = 0;
    if (active_) previous_ = std::signal(SIGINT, on_sigint);
  }
  ~SigintGuard() {
    if (active_ && previous_ != SIG_ERR) std::signal(SIGINT, previous_);
  }
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

 private:
  bool active_;
  void (*previous_)(int) = SIG_DFL;
};

using Clock = std::chrono::steady_clock;

/// "12.3 %  4.5e+06 steps/s  7 s left" on one refreshed stderr line.
class Progress {
 public:
  Progress(bool enabled, std::int64_t total) : enabled_(enabled), total_(total), start_(Clock::now()) {
    last_ = start_;
  }
  // Looking at the clock costs ~20 ns; do it every kEvery steps only.
  static constexpr std::int64_t kEvery = 512;
  void update(std::int64_t done) {
    if (!enabled_ || done % kEvery != 0) return;
    const auto now = Clock::now();
    if (now - last_ < std::chrono::milliseconds(500)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = done / std::max(elapsed, 1e-9);
    const double left = (total_ - done) / std::max(rate, 1e-9);
    std::fprintf(stderr, "\r%6.1f %%  %.3g steps/s  %.0f s left   ", 100.0 * done / std::max<std::int64_t>(total_, 1),
                 rate, left);
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (shown_) {
      std::fprintf(stderr, "\r%60s\r", "");
      std::fflush(stderr);
    }
  }

 private:
  bool enabled_;
  std::int64_t total_;
  Clock::time_point start_, last_;
  bool shown_ = false;
};

bool is_one_step(IntegratorKind kind) {
  return kind != IntegratorKind::kExplicitMidpoint && kind != IntegratorKind::kLinearMultistep;
}

}  // namespace

SimulationResult run_simulation(OdeSystem& system, const IntegratorSpec& integrator, const Eigen::VectorXd& y0,
                                const SimulationOptions& options, const RowSink& sink) {
  if (!(options.step > 0.0) || !std::isfinite(options.step))
    throw std::invalid_argument("step must be a positive number of seconds");
  if (!(options.t_end >= options.t0)) throw std::invalid_argument("t_end must not be before t0");
  if (y0.size() != system.size()) {
    std::ostringstream msg;
    msg << "initial state has " << y0.size() << " entries, expected " << system.size();
    throw std::invalid_argument(msg.str());
  }
  if (!y0.allFinite()) throw std::invalid_argument("initial state is not finite");

  const double h = options.step;
  const double span = options.t_end - options.t0;
  // Steps: one-step methods shorten the last one to land on t_end; multistep
  // methods keep h and stop at the last full step.
  constexpr double kTimeSlack = 1e-9;  // of a step: absorbs rounding in span / h
  const double ratio = span / h;
  const bool one_step = is_one_step(integrator.kind);
  const std::int64_t full_steps = static_cast<std::int64_t>(std::floor(ratio + kTimeSlack));
  const bool partial_last = one_step && ratio - full_steps > kTimeSlack;
  const std::int64_t total = full_steps + (partial_last ? 1 : 0);
  std::int64_t every = options.every;
  if (every <= 0) every = std::max<std::int64_t>(1, (total + options.max_rows - 1) / std::max<std::int64_t>(options.max_rows, 1));

  auto stepper = make_stepper(integrator, system);
  SimulationResult result;
  result.step = h;
  result.integrator = integrator.name;
  result.t = options.t0;

  SigintGuard sigint(options.handle_sigint);
  Progress progress(!options.quiet && isatty(fileno(stderr)), total);
  const auto start = Clock::now();

  Eigen::VectorXd y = y0, last_good = y0;
  stepper->reset(options.t0, y0);
  sink(options.t0, y);
  result.rows = 1;
  bool last_emitted = true;

  const double y0_norm = y0.norm();
  double running_max = y0_norm;
  double trailing_max = 0.0;  // R: max |y| up to the last power-of-two step
  auto bound_now = [&]() {
    const double scale = std::max({y0_norm, options.reference_norm, trailing_max});
    // No scale yet (a system starting at rest, no reference given): only the
    // finiteness check applies until the first power-of-two step sets R.
    return scale > 0.0 ? options.divergence_factor * scale : std::numeric_limits<double>::infinity();
  };

  double t = options.t0;
  for (std::int64_t k = 1; k <= total; ++k) {
    if (g_interrupted) {
      result.status = SimulationStatus::kInterrupted;
      break;
    }
    const double t_next = (k == total && partial_last) ? options.t_end : options.t0 + k * h;
    last_good = y;
    try {
      stepper->step(t, t_next - t, y);
    } catch (const std::exception& e) {
      y = last_good;
      result.status = SimulationStatus::kFailed;
      result.message = e.what();
      break;
    }
    const double norm = y.norm();
    const double bound = bound_now();
    // Not finite is diverged whatever the bound, which is inf while the
    // system has stayed at rest (a load that jumps to inf from rest).
    if (!(norm <= bound) || !std::isfinite(norm)) {  // also catches nan
      y = last_good;
      result.status = SimulationStatus::kDiverged;
      result.norm = norm;
      result.bound = bound;
      break;
    }
    system.after_step(t_next, y);
    if (options.on_step) options.on_step(t_next, y);
    t = t_next;
    result.steps = k;
    running_max = std::max(running_max, norm);
    if ((k & (k - 1)) == 0 && options.reference_norm == 0.0) trailing_max = running_max;
    last_emitted = (k % every == 0) || k == total;
    if (last_emitted) {
      sink(t, y);
      ++result.rows;
    }
    progress.update(k);
  }
  result.t = t;
  if (!last_emitted) {
    sink(t, y);
    ++result.rows;
  }
  progress.finish();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.newton = stepper->newton_statistics();
  return result;
}

std::string describe(const SimulationResult& r) {
  std::ostringstream out;
  out.precision(5);
  switch (r.status) {
    case SimulationStatus::kCompleted:
      out << "completed " << r.steps << " steps of " << r.integrator << " (step " << r.step << " s) to t = " << r.t
          << " s";
      break;
    case SimulationStatus::kDiverged:
      out << "diverged at t = " << r.t + r.step << " s (|y| = " << r.norm << " exceeds the bound " << r.bound
          << ") with " << r.integrator << ", step " << r.step;
      break;
    case SimulationStatus::kInterrupted:
      out << "interrupted at t = " << r.t << " s after " << r.steps << " steps";
      break;
    case SimulationStatus::kFailed:
      out << "failed at t = " << r.t << " s: " << r.message;
      break;
  }
  return out.str();
}

}  // namespace mbfe::runtime
