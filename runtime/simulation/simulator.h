// A simulation you can drive (like Drake's Simulator::AdvanceTo): made from an
// assembled model and a request, it holds the system the request asks for
// (rigid, beams in modal coordinates, or coupled in the formulation the
// request and the model choose), the integrator and the state. advance_to(t)
// steps to t; between calls the caller reads and sets the state, reads the
// outputs, or sets loads.
//
//   runtime::Simulator sim(model, request);        // the initial state: static start, projection
//   sim.advance_to(0.3);
//   sim.set_beam_load("deck", 10.0, [](double t) { return -5e3 * std::sin(20.0 * (t - 0.3)); });
//   sim.advance_to(sim.t_end());
//   const std::vector<double>& row = sim.outputs();  // layout() names the columns
//
// simulate() (simulate.h) is a loop over one. Steps follow the fixed grid of
// the request (t_k = k step, the last one shortened to land on t_end), so
// advance_to(t) stops at the last grid time at or before t; a run that
// diverges or fails stops there, keeps its last good state and says why
// in report(). Nothing here handles a signal or prints: the caller's monitor
// decides when to stop early.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runtime/integrators/simulation_driver.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

namespace detail {
class ModelRun;
}

class Simulator {
 public:
  /// The model must outlive the simulator.
  /// @throws InvalidRequest / InvalidInput for a request this model cannot
  ///         run (a field no model runs, an integrator this kind of model does
  ///         not take, --adjust on without an adjustment block, an unknown
  ///         probe beam, an initial state that violates the contacts with
  ///         strict, no static equilibrium).
  Simulator(const AssembledModel& model, const SimulationRequest& request);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// The output columns and their units.
  const OutputLayout& layout() const;
  /// What the user should hear about the start (a projection onto the
  /// contacts; an adjustment estimate above 1 %, runtime/simulation/adjustment_estimate.h).
  const std::vector<std::string>& notices() const;
  /// What is integrated ("adjusted damping, partitioned formulation, ...").
  const std::string& variant() const;

  double time() const;          // s, the state's time
  double step() const;          // s, the step taken
  double t_end() const;         // s
  std::int64_t steps() const;   // accepted so far
  std::int64_t total_steps() const;
  /// Reached t_end, or stopped (diverged, failed, interrupted).
  bool finished() const;
  /// kCompleted while the run goes well (and once it reached t_end).
  SimulationStatus status() const;

  /// Steps while the next grid time is at or before t (and t_end), asking
  /// `keep_going` before every step. Returns the status: kCompleted when it
  /// got there, or why it stopped.
  SimulationStatus advance_to(double t, const StepMonitor& keep_going = {});
  /// Takes up to n steps (the same checks).
  SimulationStatus advance_steps(std::int64_t n, const StepMonitor& keep_going = {});

  /// The full coordinates q = [q_b; q_c] (rigid coordinates in model order,
  /// then every beam's free DOFs) and their rates at the current state.
  void state(Eigen::VectorXd& q, Eigen::VectorXd& qd);
  /// Sets the state at the current time from full coordinates (projected onto
  /// the contacts; driven coordinates follow their motion whatever given).
  /// Steppers with history start again from it.
  /// @throws InvalidInput for vectors of the wrong size or not finite.
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// The output values at the current state, layout() order.
  /// @throws std::runtime_error for a fault evaluating them (a contact).
  const std::vector<double>& outputs();
  /// The row at the current state for an observer (q and qd filled as the
  /// request's state_in_rows says).
  OutputRow row();

  /// A point load on a beam, value(t) in N along the beam's transverse
  /// direction (the direction positive deflection points), from now on; it
  /// replaces one set before at the same beam and point. Beam and coupled models.
  /// @throws InvalidInput for a model without beams, an unknown beam or s off it.
  void set_beam_load(const std::string& beam, double s, std::function<double(double)> value);

  /// The run so far: status, steps, wall time spent advancing, variant,
  /// tallies; for a run that stopped early, the sentence that says why.
  SimulationReport report();
  /// A fault the caller met evaluating a row (outputs() or row() threw): the
  /// report names it even if the steps go on (the first one is kept).
  void note_row_fault(const std::string& fault);

 private:
  const AssembledModel& model_;
  SimulationRequest request_;
  std::unique_ptr<detail::ModelRun> run_;
  std::unique_ptr<FixedStepRun> steps_;
  std::vector<double> values_;
  Eigen::VectorXd q_, qd_;
  double wall_seconds_ = 0.0;
  std::string row_fault_;  // a fault met while evaluating a row, kept for the report
  std::vector<std::string> notices_;
  std::optional<AdjustmentEstimate> estimate_;  // adjusted runs
};

}  // namespace mbfe::runtime
