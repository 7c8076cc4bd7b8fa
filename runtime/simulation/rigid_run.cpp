// simulate() for a model of bodies only: y = [q; q'], y' = [q'; M^-1 (Q - F)].
#include "runtime/multibody/rigid_system.h"
#include "runtime/simulation/invalid_input.h"
#include "runtime/simulation/run_diagnosis.h"
#include "runtime/simulation/runs.h"
#include "runtime/simulation/static_start.h"
#include "runtime/simulation/time_expressions.h"

namespace mbfe::runtime::detail {

SimulationReport run_rigid(const AssembledModel& model, const SimulationRequest& request,
                           SimulationObserver& observer) {
  RigidSystem system(*model.kernels(), model.bodies());
  const int n = system.num_coordinates();
  Eigen::VectorXd q0, qd0;
  model.initial_coordinates(q0, qd0);
  Eigen::VectorXd y0(2 * n);
  y0 << q0, qd0;
  system.impose_motion(0.0, y0);
  if (request.static_start.value_or(model.ir().initial.static_start)) rigid_static_state(model.ir(), system, y0);


  OutputLayout layout;
  layout.columns.push_back("t");
  layout.units.push_back("s");
  for (int i = 0; i < 2 * n; ++i) {
    layout.columns.push_back(system.name(i));
    const ir::Body& body = model.ir().bodies[i % n];
    layout.units.push_back(i < n ? coordinate_unit(body) : rate_unit(body));
  }
  for (int d : system.driven()) {
    layout.columns.push_back(model.ir().bodies[d].name + "_drive");
    layout.units.push_back(model.ir().bodies[d].joint.type == ir::JointType::kRevolute ? "N m" : "N");
  }
  observer.begin(layout);
  std::vector<double> values(layout.columns.size());
  Eigen::VectorXd q(n), qd(n), y_out(2 * n), reactions;

  SimulationReport report;
  try {
    report.run = run_simulation(system, request.integrator, y0, driver_options(request),
                                [&](double t, const Eigen::VectorXd& y) {
                                  y_out = y;
                                  system.impose_motion(t, y_out);
                                  values[0] = t;
                                  for (int i = 0; i < 2 * n; ++i) values[1 + i] = y_out[i];
                                  if (!system.driven().empty()) {
                                    system.drive_reactions(t, y_out, reactions);
                                    for (Eigen::Index k = 0; k < reactions.size(); ++k)
                                      values[1 + 2 * n + k] = reactions[k];
                                  }
                                  q = y_out.head(n);
                                  qd = y_out.tail(n);
                                  observer.row(OutputRow{t, values, q, qd});
                                });
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(e.what());
  }
  report.message = diagnose_run(report.run, std::nullopt);
  if (report.run.status == SimulationStatus::kDiverged || report.run.status == SimulationStatus::kFailed) {
    // A load or motion that is no longer finite broke the run, not the integrator.
    const std::string cause = non_finite_expression(model.ir(), report.run.t, report.run.step);
    if (!cause.empty()) report.message = cause;
  }
  return report;
}

}  // namespace mbfe::runtime::detail
