// Runs an OdeSystem with one integrator at a fixed step from t0 to t_end:
// FixedStepRun takes the steps one at a time and watches for divergence;
// run_simulation loops over it and hands decimated rows to a sink. Whoever
// runs it decides when to stop early (`keep_going`: a caller's Ctrl-C, a
// deadline) and shows progress; the runtime installs no signal handler and
// prints nothing.
//
//   runtime::SimulationOptions opt;
//   opt.step = 1.4e-5; opt.t_end = 1.0;
//   auto result = runtime::run_simulation(system, runtime::parse_integrator("forward_euler"),
//                                         y0, opt, [&](double t, const Eigen::VectorXd& y) {
//                                           write_csv_row(t, y); });
//   if (result.status == runtime::SimulationStatus::kDiverged) { ... exit 3 ... }
//
// Rows: the sink receives t0 and y0 first, then the state after every
// `every`-th step, and always the last state reached (t_end, or the last state
// that passed the divergence check, or the state when interrupted). The sink is
// called from the simulating thread; it owns the output and its flushing.
//
// Divergence: after every step, y is "diverged" when its Euclidean norm is not
// finite or exceeds
//     bound = divergence_factor * max(|y0|, reference_norm, R)
// where R is the largest |y| seen up to the last step number that is a power
// of two (so R trails the run by at most half its length: a bounded response
// raises R, an instability grows by the factor within a stretch of steps).
// R is used only when no reference_norm is given (R = 0 otherwise): a known
// scale catches an instability as soon as it is 1e6 times that scale.
// divergence_factor defaults to 1e6; reference_norm is a scale the caller
// knows (for a beam: the norm of its static state under the load), 0 if none.
// While all three are 0 (a system at rest, no reference) only finiteness is
// checked. Because R follows the run, a slow instability is caught late (in
// the worst case when it overflows); pass reference_norm to catch it early.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "runtime/integrators/integrator.h"
#include "runtime/integrators/ode_system.h"
#include "runtime/integrators/simulation_result.h"

namespace mbfe::runtime {

struct SimulationOptions {
  double t0 = 0.0;     // s
  double step = 0.0;   // s, > 0
  double t_end = 0.0;  // s, >= t0; the last step is shortened to land on t_end
                       // (one-step methods only; multistep methods stop at the
                       // last full step <= t_end + step * 1e-9). A step longer
                       // than t_end - t0 is shortened to it: one step.
  /// Emit every `every`-th step. 0 = automatic: every = ceil(steps / max_rows),
  /// so at most about max_rows + 2 rows are written.
  std::int64_t every = 0;
  std::int64_t max_rows = 10000;  // used when every == 0
  double divergence_factor = 1.0e6;
  double reference_norm = 0.0;    // see the header comment
  /// Called after every accepted step (after OdeSystem::after_step) with the
  /// state the step reached; empty = nothing.
  std::function<void(double t, const Eigen::VectorXd& y)> on_step;
  /// Asked before every step with the time reached and the steps taken;
  /// false stops the run there (status kInterrupted). Empty = go on.
  std::function<bool(double t, std::int64_t steps)> keep_going;
};

using RowSink = std::function<void(double t, const Eigen::VectorXd& y)>;

/// One fixed-step run, a step at a time: what run_simulation loops over, and
/// what a caller that steps a model between its own actions holds.
class FixedStepRun {
 public:
  /// Starts at options.t0 from y0 (size system.size()); `system` must outlive
  /// the run. @throws std::invalid_argument for bad options (step <= 0,
  /// t_end < t0, too many steps, y0 of the wrong size or not finite) or an
  /// integrator the system cannot take.
  FixedStepRun(OdeSystem& system, const IntegratorSpec& integrator, const Eigen::VectorXd& y0,
               const SimulationOptions& options);
  ~FixedStepRun();

  double t() const { return t_; }
  const Eigen::VectorXd& y() const { return y_; }
  std::int64_t steps() const { return result_.steps; }
  /// Steps to t_end (the last one shortened to land on it, one-step methods).
  std::int64_t total_steps() const { return total_; }
  /// The step h the run takes (a step longer than the run is shortened to it).
  double step_size() const { return h_; }
  /// The time step k ends at.
  double time_of(std::int64_t k) const;
  /// The last step, from the steps taken to total_steps(), that ends at or
  /// before t: the largest such k with time_of(k) <= t, or steps() when the
  /// next step ends after t (or t is NaN). Found from (t - t0) / h and
  /// corrected against time_of, in a few operations however far t is.
  std::int64_t last_step_by(double t) const;
  /// Reached t_end, or stopped (failed, diverged, interrupted).
  bool finished() const { return result_.steps >= total_ || result_.status != SimulationStatus::kCompleted; }
  /// Takes the next step (after asking keep_going): true if it was accepted;
  /// false when the run has finished or this step failed, diverged or was
  /// stopped (the state is then the last one accepted; result() says why).
  bool step();
  /// Stops the run here (status kInterrupted): a caller's decision.
  void interrupt();
  /// Replaces the state at the current time (a caller set it): steppers with
  /// history start again from it.
  void reset_state(const Eigen::VectorXd& y);
  /// The run so far (Newton counts brought up to date; wall_seconds is the
  /// caller's to fill).
  const SimulationResult& result();

 private:
  OdeSystem& system_;
  SimulationOptions options_;
  std::unique_ptr<Stepper> stepper_;
  double h_ = 0.0, t_ = 0.0;
  std::int64_t total_ = 0;
  bool partial_last_ = false;
  Eigen::VectorXd y_, last_good_;
  double y0_norm_ = 0.0, running_max_ = 0.0, trailing_max_ = 0.0;
  SimulationResult result_;
};

/// Integrates `system` from y0 (size system.size()). Never throws for a
/// numerical fault of the system: that is kFailed with `message` (rows so far
/// emitted). @throws std::invalid_argument for bad options (step <= 0,
/// t_end < t0, more than 2^53 steps, y0 of the wrong size) or an integrator
/// the system cannot take.
SimulationResult run_simulation(OdeSystem& system, const IntegratorSpec& integrator,
                                const Eigen::VectorXd& y0, const SimulationOptions& options,
                                const RowSink& sink);

/// "diverged at t = 0.0123 s: step 1.5e-05 ..." without the limit part:
/// `diverged at t = T s (|y| = N exceeds the bound B) with forward_euler, step H`.
/// Callers that know the stable limit print their own sentence.
std::string describe(const SimulationResult& result);

}  // namespace mbfe::runtime
