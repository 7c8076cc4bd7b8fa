#include "runtime/integrators/simulation_driver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

using Clock = std::chrono::steady_clock;

bool is_one_step(IntegratorKind kind) {
  return kind != IntegratorKind::kExplicitMidpoint && kind != IntegratorKind::kLinearMultistep;
}

}  // namespace

FixedStepRun::FixedStepRun(OdeSystem& system, const IntegratorSpec& integrator, const Eigen::VectorXd& y0,
                           const SimulationOptions& options)
    : system_(system), options_(options) {
  if (!(options.step > 0.0) || !std::isfinite(options.step))
    throw std::invalid_argument("step must be a positive number of seconds");
  if (!(options.t_end >= options.t0)) throw std::invalid_argument("t_end must not be before t0");
  if (y0.size() != system.size()) {
    std::ostringstream msg;
    msg << "initial state has " << y0.size() << " entries, expected " << system.size();
    throw std::invalid_argument(msg.str());
  }
  if (!y0.allFinite()) throw std::invalid_argument("initial state is not finite");

  const double span = options.t_end - options.t0;
  // A step longer than the whole run is shortened to the run: one step to
  // t_end (it took none and called that completed).
  h_ = options.step > span && span > 0.0 ? span : options.step;
  // Steps: one-step methods shorten the last one to land on t_end; multistep
  // methods keep h and stop at the last full step.
  constexpr double kTimeSlack = 1e-9;  // of a step: absorbs rounding in span / h
  const double ratio = span / h_;
  // Step numbers k and times t0 + k h stay exact up to 2^53 steps; beyond,
  // the count would not even fit the int64 it is cast to.
  constexpr double kMaxSteps = 9007199254740992.0;  // 2^53
  if (!(ratio <= kMaxSteps)) {
    std::ostringstream msg;
    msg << "the run needs " << ratio << " steps ((t_end - t0) / step = " << span << " s / " << h_
        << " s), more than the limit of " << static_cast<std::int64_t>(kMaxSteps) << " (2^53)";
    throw std::invalid_argument(msg.str());
  }
  const bool one_step = is_one_step(integrator.kind);
  const std::int64_t full_steps = static_cast<std::int64_t>(std::floor(ratio + kTimeSlack));
  partial_last_ = one_step && ratio - full_steps > kTimeSlack;
  total_ = full_steps + (partial_last_ ? 1 : 0);

  stepper_ = make_stepper(integrator, system);
  result_.step = h_;
  result_.integrator = integrator.name;
  result_.t = options.t0;
  t_ = options.t0;
  y_ = y0;
  last_good_ = y0;
  stepper_->reset(options.t0, y0);
  y0_norm_ = y0.norm();
  running_max_ = y0_norm_;
}

FixedStepRun::~FixedStepRun() = default;

double FixedStepRun::time_of(std::int64_t k) const {
  return (k == total_ && partial_last_) ? options_.t_end : options_.t0 + static_cast<double>(k) * h_;
}

std::int64_t FixedStepRun::last_step_by(double t) const {
  const std::int64_t from = result_.steps;
  const double x = (t - options_.t0) / h_;
  std::int64_t k = from;
  if (x >= static_cast<double>(total_)) k = total_;
  else if (x > static_cast<double>(from)) k = static_cast<std::int64_t>(std::floor(x));  // < total_ <= 2^53
  // x is off by rounding from the grid t0 + k h (and the last step of a
  // one-step method ends at t_end, short of it): a step or so either way.
  while (k < total_ && time_of(k + 1) <= t) ++k;
  while (k > from && time_of(k) > t) --k;
  return k;
}

bool FixedStepRun::step() {
  if (finished()) return false;
  if (options_.keep_going && !options_.keep_going(t_, result_.steps)) {
    result_.status = SimulationStatus::kInterrupted;
    return false;
  }
  const std::int64_t k = result_.steps + 1;
  const double t_next = time_of(k);
  last_good_ = y_;
  try {
    stepper_->step(t_, t_next - t_, y_);
  } catch (const std::exception& e) {
    y_ = last_good_;
    result_.status = SimulationStatus::kFailed;
    result_.message = e.what();
    return false;
  }
  // R: the largest |y| up to the last power-of-two step (the header says why).
  const double scale = std::max({y0_norm_, options_.reference_norm, trailing_max_});
  // No scale yet (a system starting at rest, no reference given): only the
  // finiteness check applies until the first power-of-two step sets R.
  const double bound =
      scale > 0.0 ? options_.divergence_factor * scale : std::numeric_limits<double>::infinity();
  const double norm = y_.norm();
  // Not finite is diverged whatever the bound, which is inf while the
  // system has stayed at rest (a load that jumps to inf from rest).
  if (!(norm <= bound) || !std::isfinite(norm)) {  // also catches nan
    y_ = last_good_;
    result_.status = SimulationStatus::kDiverged;
    result_.norm = norm;
    result_.bound = bound;
    return false;
  }
  system_.after_step(t_next, y_);
  if (options_.on_step) options_.on_step(t_next, y_);
  t_ = t_next;
  result_.t = t_;
  result_.steps = k;
  running_max_ = std::max(running_max_, norm);
  if ((k & (k - 1)) == 0 && options_.reference_norm == 0.0) trailing_max_ = running_max_;
  return true;
}

void FixedStepRun::interrupt() {
  if (result_.status == SimulationStatus::kCompleted) result_.status = SimulationStatus::kInterrupted;
}

void FixedStepRun::reset_state(const Eigen::VectorXd& y) {
  if (y.size() != y_.size() || !y.allFinite())
    throw std::invalid_argument("the state set has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(y_.size()) + ", all finite");
  y_ = y;
  last_good_ = y;
  stepper_->reset(t_, y_);
}

const SimulationResult& FixedStepRun::result() {
  result_.newton = stepper_->newton_statistics();
  return result_;
}

SimulationResult run_simulation(OdeSystem& system, const IntegratorSpec& integrator, const Eigen::VectorXd& y0,
                                const SimulationOptions& options, const RowSink& sink) {
  const auto start = Clock::now();
  FixedStepRun run(system, integrator, y0, options);
  const std::int64_t total = run.total_steps();
  std::int64_t every = options.every;
  if (every <= 0) every = std::max<std::int64_t>(1, (total + options.max_rows - 1) / std::max<std::int64_t>(options.max_rows, 1));
  std::int64_t rows = 1;
  sink(run.t(), run.y());
  bool last_emitted = true;
  while (run.step()) {
    const std::int64_t k = run.steps();
    last_emitted = (k % every == 0) || k == total;
    if (last_emitted) {
      sink(run.t(), run.y());
      ++rows;
    }
  }
  if (!last_emitted) {
    sink(run.t(), run.y());
    ++rows;
  }
  SimulationResult result = run.result();
  result.rows = rows;
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
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
