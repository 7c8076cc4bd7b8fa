// One entry to simulate any model: rigid (bodies only), beams (no bodies) or
// coupled (bodies, beams, contacts). A request (integrator, step, end time,
// probes, ...) goes in; output rows go to an observer as they are computed; a
// report with the run's status and, for a run that did not complete, the one
// sentence that explains it comes out.
//
//   runtime::AssembledModel model(ir, kernels);
//   runtime::SimulationRequest request;
//   request.integrator = runtime::parse_integrator("rk4");
//   request.step = 1e-3;
//   request.t_end = 2.0;
//   MyObserver observer;                        // begin(layout), then row(...) per output row
//   const runtime::SimulationReport report = runtime::simulate(model, request, observer);
//   if (report.run.status != runtime::SimulationStatus::kCompleted) std::cerr << report.message;
//
// Rows: t, the rigid coordinates (model order), the beam coordinates
// (<beam>_w<node>, <beam>_dw<node>: free DOFs in contract order) or the probe
// columns, the rates of all those (<name>_dot), and for a coupled model the
// contact forces (lambda_<contact> for a slider_pin, lambda_<contact>_1/_2
// for a pin, N) and phi_abs = max |Phi| (m). Which rows: see
// runtime/integrators/simulation_driver.h (the first, every `every`-th, the last).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "runtime/multibody/contact_springs.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/beam_probes.h"

namespace mbfe::runtime {

/// Coupled models: which formulation of the constraints (docs/partitioning.md).
enum class CoupledFormulation {
  kPartitioned,  // coordinate partitioning, eqs (16)-(17); |Phi| closed by Newton every step
  kAugmented,    // multipliers; a cross-check, |Phi| drifts
};

struct SimulationRequest {
  IntegratorSpec integrator;
  double step = 0.0;   // s, > 0
  double t_end = 0.0;  // s, > 0
  /// Write every `every`-th step; 0 = automatic (at most about 10,000 rows).
  std::int64_t every = 0;
  /// Beams with their adjusted damping; absent = when some beam has an
  /// active adjustment block.
  std::optional<bool> adjust;
  /// Beam and coupled models: these columns instead of every beam coordinate.
  std::vector<ProbeSpec> probes;
  CoupledFormulation formulation = CoupledFormulation::kPartitioned;
  /// Progress line on stderr (when it is a terminal) unless quiet.
  bool quiet = true;
  /// The observer reads OutputRow::q and qd. Rigid runs fill them anyway, and
  /// so do coupled runs but those with beams in split coordinates and probes;
  /// those and beam runs fill them only when asked, since the nodal
  /// coordinates cost a pass over the kept modes (n^2 per row for a beam run).
  bool state_in_rows = false;
  /// Ctrl-C stops the run after the current step (status kInterrupted).
  bool handle_sigint = true;
  /// Start from the static equilibrium at t = 0 of everything not driven;
  /// absent = as the model's `initial: {static: ...}` says.
  std::optional<bool> static_start;
  /// An initial state that violates the contacts is an error (InvalidInput)
  /// instead of being projected onto them with a notice.
  bool strict = false;
};

/// The output columns, known before the first row, with their units
/// ("s", "m", "rad", "m/s", "rad/s", "N", "1" for a beam slope, "1/s" for its rate).
struct OutputLayout {
  std::vector<std::string> columns;
  std::vector<std::string> units;
};

/// One output row: `values` in layout order, and the full state it came from:
/// q = [q_b; q_c] (rigid coordinates, then every beam's free DOFs) and its rates
/// (empty unless asked for in some runs: see SimulationRequest::state_in_rows).
struct OutputRow {
  double t = 0.0;
  const std::vector<double>& values;
  const Eigen::VectorXd& q;
  const Eigen::VectorXd& qd;
};

class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  /// Called once, before the first row.
  virtual void begin(const OutputLayout& /*layout*/) {}
  /// Called for every output row, from the simulating thread.
  virtual void row(const OutputRow& row) = 0;
  /// Something the user should know that is not an error, in one or more
  /// lines: the initial state was projected onto the contacts (which
  /// coordinates moved, by how much). The tool prints it on stderr.
  virtual void notice(const std::string& /*text*/) {}
};

struct SimulationReport {
  SimulationResult run;  // status, steps, time reached, wall time
  /// What was integrated, for messages: "adjusted damping", "original
  /// damping, partitioned formulation"; empty for a rigid model.
  std::string variant;
  /// Empty when the run completed; otherwise the one sentence that says why it
  /// did not: "diverged at t = 0.0041 s: step 1.5e-05 exceeds forward_euler's
  /// stable limit 1.4597e-05 (fastest eigenvalue -1.3702e5)", "failed at t = ...
  /// s: <the fault>", "interrupted at t = ... s".
  std::string message;
  /// Coupled models: lift-offs and time off contact of each slider_spring contact.
  std::vector<SpringContactTally> springs;
  /// Coupled models: slackenings and time slack of each link that can go slack.
  std::vector<LinkSlackTally> links;
};

/// Runs the request. Numerical faults (divergence, a singular mass matrix, a
/// slider off its beam, Ctrl-C) end the run with a status and a message; every
/// row computed before them has been handed to the observer.
/// @throws InvalidInput for a request this model cannot run (generalized_alpha
///         on a nonlinear model, probes on a rigid model, --adjust on without an
///         adjustment block, an unknown probe beam, an initial state that
///         violates the contacts, a bad step or end time).
/// @throws ir::ModelError for a load or motion that is not finite where the
///         run first evaluates it (runtime/simulation/time_expressions.h); one
///         that becomes non-finite later ends the run with a message naming it.
SimulationReport simulate(const AssembledModel& model, const SimulationRequest& request,
                          SimulationObserver& observer);

}  // namespace mbfe::runtime
