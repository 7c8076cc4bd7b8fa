// One entry to simulate any model: rigid (bodies only), beams (no bodies) or
// coupled (bodies, beams, contacts). A request (integrator, step, end time,
// probes, ...; simulation_types.h) goes in; output rows go to an observer as
// they are computed; a report with the run's status and, for a run that did
// not complete, the one sentence that explains it comes out.
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
// It is a loop over a Simulator (simulator.h), which a caller can also drive
// itself. Rows: t, the rigid coordinates (model order), the beam coordinates
// (<beam>_w<node>, <beam>_dw<node>: free DOFs in contract order) or the probe
// columns, the rates of all those (<name>_dot), and for a coupled model the
// contact forces (lambda_<contact> for a slider_pin, lambda_<contact>_1/_2
// for a pin, N), phi_abs = max |Phi| (m), force_ and deflection_ of each
// slider_spring, tension_ of each link and <body>_drive of each driven joint.
// Which rows: the first, every `every`-th, the last.
#pragma once

#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

/// Runs the request. Numerical faults (divergence, a singular mass matrix, a
/// slider off its beam) and `keep_going` saying stop end the run with a
/// status and a message; every row computed before them has been handed to
/// the observer.
/// @throws InvalidRequest / InvalidInput for a request this model cannot run
///         (generalized_alpha on a nonlinear model, probes on a rigid model,
///         adjust on without an adjustment block, an unknown probe beam, an
///         initial state that violates the contacts with strict, a bad step
///         or end time).
/// @throws ir::ModelError for a load or motion that is not finite where the
///         run first evaluates it (runtime/simulation/time_expressions.h); one
///         that becomes non-finite later ends the run with a message naming it.
SimulationReport simulate(const AssembledModel& model, const SimulationRequest& request,
                          SimulationObserver& observer, const StepMonitor& keep_going = {});

/// What a run of `request` on `model` cannot do, found from the model file
/// alone, before the model is assembled (the modal analysis of a large beam
/// takes seconds): an acceleration probe on a beam of policy truncate in an
/// adjusted coupled run (the truncated beam steps in its kept modes, which hold
/// no nodal acceleration). Runs the checks simulate() makes again later.
/// @throws InvalidInput at the beam's adjustment block, naming the probe and
///         the beam it is on.
void check_request_early(const ir::Model& model, const SimulationRequest& request);

}  // namespace mbfe::runtime
