// What a caller of a simulation sees: the request (integrator, step, end time,
// probes, ...), the layout and rows of its output, the observer that receives
// them, and the report of how the run went. simulate() (simulate.h) and the
// Simulator (simulator.h) take and give these; the public API hands them on.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "runtime/integrators/integrator_spec.h"
#include "runtime/integrators/simulation_result.h"

namespace mbfe::runtime {

/// Coupled models: which formulation of the constraints (docs/partitioning.md).
enum class CoupledFormulation {
  kPartitioned,  // coordinate partitioning, eqs (16)-(17); |Phi| closed by Newton every step
  kAugmented,    // multipliers; a cross-check, |Phi| drifts
};

/// A probe as asked for: BEAM@S (the displacement, m) or BEAM@S:acc (the
/// acceleration, m/s^2), S in m along the beam; or BODY:acc, the second
/// derivative of a body's joint coordinate (m/s^2 or rad/s^2).
struct ProbeSpec {
  std::string label;  // as written, e.g. "beam1@0.5" or "beam1@0.5:acc": the column name
  std::string beam;   // the beam's name, or the body's (body)
  double s = 0.0;     // m
  bool acceleration = false;  // ":acc"
  bool body = false;          // BODY:acc
};

/// Parses "BEAM@S", "BEAM@S:acc" or "BODY:acc". @throws InvalidRequest (field "probes")
/// naming the text for any other form.
ProbeSpec parse_probe(const std::string& text);

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
  /// The observer reads OutputRow::q and qd. Rigid runs fill them anyway, and
  /// so do coupled runs but those with beams in split coordinates and probes;
  /// those and beam runs fill them only when asked, since the nodal
  /// coordinates cost a pass over the kept modes (n^2 per row for a beam run).
  bool state_in_rows = false;
  /// Start from the static equilibrium at t = 0 of everything not driven;
  /// absent = as the model's `initial: {static: ...}` says.
  std::optional<bool> static_start;
  /// An initial state that violates the contacts is an error (InvalidInput)
  /// instead of being projected onto them with a notice.
  bool strict = false;
};

/// @throws InvalidRequest naming the field of `request` that no model can run
/// (a step or end time not > 0 or not finite, a negative every).
void check_request(const SimulationRequest& request);

/// Asked before every step with the time reached and the steps taken; false
/// stops the run there (status kInterrupted). What a caller uses for Ctrl-C,
/// a deadline or a progress line; the runtime handles no signal and prints
/// nothing.
using StepMonitor = std::function<bool(double t, std::int64_t steps)>;

/// The output columns, known before the first row, with their units
/// ("s", "m", "rad", "m/s", "rad/s", "N", "N m", "1" for a beam slope, "1/s" for its rate).
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

/// Lift-offs and time off contact of a slider_spring contact over a run,
/// counted on accepted steps while the contact point is over its beam. In
/// contact means delta > 0 (a unilateral damper may still hold N at 0 there
/// for a moment as the surfaces part; that is not a lift-off).
struct SpringContactTally {
  std::string name;
  int lift_offs = 0;        // transitions from delta > 0 to delta <= 0
  double time_off = 0.0;    // s with delta <= 0 while over the beam
  bool in_contact = false;  // at the last accepted step
  bool seen = false;        // the point was over the beam at an accepted step
  bool touched = false;     // delta > 0 over the beam at an accepted step
  /// Ground-frame position (m) of the contact point at the first and at the
  /// last accepted step; NaN when not known (a run without accepted steps).
  std::array<double, 2> start{NAN, NAN}, end{NAN, NAN};
};

/// Slack events and time slack of a link over a run, counted on accepted
/// steps (like SpringContactTally for contacts).
struct LinkSlackTally {
  std::string name;
  int slackenings = 0;      // transitions from taut to slack
  double time_slack = 0.0;  // s
  bool slack = false;       // at the last accepted step
  bool seen = false;        // a step has been counted (a link slack from the start has not slackened)
};

/// One place of an adjusted beam where a force acts or a displacement is
/// read, and what the adjustment changes there (docs/damping-adjustment.md,
/// "The accuracy estimate").
struct AdjustmentEstimatePoint {
  std::string what;   // "contact 'wheel' (slider_spring)", "link 'd3' end a", "point load", "moving load", "probe deck@15"
  std::string beam;   // the beam's name
  double s = 0.0;     // m along the beam: the place, or for a moving point the one of the largest change on its path
  bool moving = false;               // the point travels along the beam (the figures are the largest on its path)
  double series_compliance = 0.0;    // m/N: 1/k of the spring in series (slider_spring, link), else 0
  double omega = 0.0;                // rad/s: the force's frequency there (a body on a contact spring), 0 for quasi-static
  double compliance = 0.0;           // m/N: the original static point compliance e^T K^-1 e at s
  double static_change = 0.0;        // relative change of the static compliance (c_s + e^T K^-1 e) the adjustment makes
  double dynamic_change = 0.0;       // relative change of the receptance at omega (over the quasi-static compliance there)
  double changed_share = 0.0;        // the changed modes' share of the quasi-static compliance at omega
  double estimate = 0.0;             // max(static_change, dynamic_change)
  double band_change = 0.0;          // the largest relative change of the receptance over [0, omega] (>= estimate)
  double omega_band = 0.0;           // rad/s: the frequency of band_change (0: the static change)
};

/// What the adjustment changes in one contact's force over a run, by the
/// linearised run of both models (docs/damping-adjustment.md, "The accuracy
/// estimate").
struct LinearisedContactChange {
  std::string contact;       // the slider_spring contact's name
  double relative = 0.0;     // max_t |F_adj - F_orig| / max_t |F_orig|
  double peak_change = 0.0;  // (max_t F_adj - max_t F_orig) / max_t F_orig (signed)
  double peak = 0.0;         // N: max_t |F_orig|
};

/// The linearised run's estimate: every slider_spring contact's change, the
/// worst of them, and what the two runs took.
struct LinearisedEstimate {
  std::vector<LinearisedContactChange> contacts;
  int worst = -1;                 // index into contacts of the largest relative change, -1 when no contact pressed
  double step = 0.0;              // s, Newmark's step
  int steps = 0;
  double omega_excitation = 0.0;  // rad/s: the fastest excitation the step resolves
  double seconds = 0.0;           // wall time of the set-up and both runs
  int unconverged_steps = 0;      // steps whose contact and link forces did not settle (both runs)
};

/// The estimate of an adjusted run, made before its first step.
struct AdjustmentEstimate {
  std::vector<AdjustmentEstimatePoint> points;
  int largest = -1;        // index into points of the largest point estimate, -1 when none
  /// The estimate: the linearised run's worst relative change of a contact
  /// force where that run applies, else points[largest].estimate (0 when
  /// there is neither).
  double max = 0.0;
  /// Where max is: "contact 'tyre' (slider_spring)", a point's `what`, or
  /// empty when there is no estimate.
  std::string where;
  /// The linearised run's figures, absent where it does not apply; then
  /// linearised_unavailable says why.
  std::optional<LinearisedEstimate> linearised;
  std::string linearised_unavailable;
  /// Every adjusted beam's omega_limit (rad/s), and whether it was chosen
  /// for a tolerance (omega_limit: auto).
  struct Limit {
    std::string beam;
    double omega_limit = 0.0;
    bool chosen = false;
  };
  std::vector<Limit> limits;
  /// Adjusted beams the estimate does not cover, each with the reason
  /// ("'wire': scope joined").
  std::vector<std::string> not_estimated;
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
  /// Adjusted runs: what the adjustment changes where forces act (absent for
  /// a run of the original model).
  std::optional<AdjustmentEstimate> adjustment_estimate;
};

/// "completed", "diverged", "interrupted" or "failed": how a report names
/// its run's end (a run that completed but whose last row failed is "failed").
const char* status_name(const SimulationReport& report);

}  // namespace mbfe::runtime
