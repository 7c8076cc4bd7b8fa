#include "runtime/simulation/simulator.h"

#include <algorithm>
#include <cmath>

#include "runtime/errors/invalid_input.h"
#include "runtime/simulation/adjustment_estimate.h"
#include "runtime/simulation/massless_joints.h"
#include "runtime/simulation/model_run.h"
#include "runtime/simulation/run_diagnosis.h"
#include "runtime/simulation/time_expressions.h"

namespace mbfe::runtime {

namespace {

using Clock = std::chrono::steady_clock;

// Grid times a hair above t count as t (rounding in t0 + k h).
constexpr double kGridSlack = 1e-9;  // of a step

}  // namespace

Simulator::Simulator(const AssembledModel& model, const SimulationRequest& request)
    : model_(model), request_(request) {
  check_request(request);
  // Runs start at t = 0 (the options' t0 is left alone).
  check_time_expressions(model.ir(), model.kernels(), 0.0, request.t_end);
  // The static start names a joint that moves no mass itself; from the given
  // state the first step would divide by its zero mass.
  if (!request.static_start.value_or(model.ir().initial.static_start)) refuse_massless_joints(model.ir());
  run_ = detail::make_model_run(model, request);
  SimulationOptions options = run_->options();
  options.step = request.step;
  options.t_end = request.t_end;
  options.every = request.every;
  options.on_step = [this](double t, const Eigen::VectorXd& y) { run_->accepted(t, y); };
  try {
    steps_ = std::make_unique<FixedStepRun>(run_->system(), request.integrator, run_->initial_state(), options);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(e.what());
  }
  values_.resize(run_->layout().columns.size());
  notices_ = run_->notices();
  if (run_->adjusted()) {
    // From the run's own initial state, over the run.
    LinearisationPoint start;
    if (model.kind() == ModelKind::kCoupled) run_->full_state(0.0, run_->initial_state(), start.q, start.qd);
    start.static_start = request.static_start.value_or(model.ir().initial.static_start);
    start.t_end = request.t_end;
    start.step_budget = static_cast<int>(
        std::min(kLinearisedStepsPerRunStep * std::ceil(request.t_end / request.step), double{kLinearisedMaxSteps}));
    estimate_ = estimate_adjustment(model, request.probes, &start);
    if (std::string line = adjustment_notice(*estimate_, model.ir()); !line.empty()) notices_.push_back(std::move(line));
  }
}

Simulator::~Simulator() = default;

const OutputLayout& Simulator::layout() const { return run_->layout(); }
const std::vector<std::string>& Simulator::notices() const { return notices_; }
const std::string& Simulator::variant() const { return run_->variant(); }
double Simulator::time() const { return steps_->t(); }
double Simulator::step() const { return steps_->step_size(); }
double Simulator::t_end() const { return request_.t_end; }
std::int64_t Simulator::steps() const { return steps_->steps(); }
std::int64_t Simulator::total_steps() const { return steps_->total_steps(); }
bool Simulator::finished() const { return steps_->finished(); }
SimulationStatus Simulator::status() const { return const_cast<FixedStepRun&>(*steps_).result().status; }

SimulationStatus Simulator::advance_steps(std::int64_t n, const StepMonitor& keep_going) {
  const auto start = Clock::now();
  for (std::int64_t k = 0; k < n && !steps_->finished(); ++k) {
    if (keep_going && !keep_going(steps_->t(), steps_->steps())) {
      steps_->interrupt();
      break;
    }
    if (!steps_->step()) break;
  }
  wall_seconds_ += std::chrono::duration<double>(Clock::now() - start).count();
  return status();
}

SimulationStatus Simulator::advance_to(double t, const StepMonitor& keep_going) {
  // The steps whose end is at or before t, computed, not counted: with 1e9
  // steps ahead counting them one by one took seconds before the first step.
  const std::int64_t target = steps_->last_step_by(t + kGridSlack * steps_->step_size());
  return advance_steps(target - steps_->steps(), keep_going);
}

void Simulator::state(Eigen::VectorXd& q, Eigen::VectorXd& qd) { run_->full_state(steps_->t(), steps_->y(), q, qd); }

void Simulator::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (!q.allFinite() || !qd.allFinite()) throw InvalidInput("the state set is not finite");
  steps_->reset_state(run_->state_of(steps_->t(), q, qd));
}

const std::vector<double>& Simulator::outputs() {
  run_->row(steps_->t(), steps_->y(), values_, nullptr, nullptr);
  return values_;
}

OutputRow Simulator::row() {
  run_->row(steps_->t(), steps_->y(), values_, &q_, &qd_);
  return OutputRow{steps_->t(), values_, q_, qd_};
}

void Simulator::set_beam_load(const std::string& beam, double s, std::function<double(double)> value) {
  run_->set_beam_load(beam, s, std::move(value));
}

SimulationReport Simulator::report() {
  SimulationReport report;
  report.run = steps_->result();
  report.run.wall_seconds = wall_seconds_;
  report.variant = run_->variant();
  run_->fill(report);
  report.adjustment_estimate = estimate_;
  if (report.run.status == SimulationStatus::kCompleted && row_fault_.empty()) return report;
  if (report.run.status != SimulationStatus::kInterrupted && row_fault_.empty()) {
    // A load or motion of the bodies that is no longer finite broke the run, not the integrator.
    const std::string cause = non_finite_expression(model_.ir(), report.run.t, report.run.step);
    if (!cause.empty()) {
      report.message = cause;
      return report;
    }
  }
  std::optional<StepLimit> limit;
  if (report.run.status != SimulationStatus::kInterrupted) limit = run_->stable_limit(request_.integrator);
  report.message = diagnose_run(report.run, limit, row_fault_);
  return report;
}

void Simulator::note_row_fault(const std::string& fault) {
  if (row_fault_.empty()) row_fault_ = fault;
}

}  // namespace mbfe::runtime
